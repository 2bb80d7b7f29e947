// The files `eval` writes for people, to compare two runs' reports byte for byte.
#pragma once

#include <filesystem>
#include <map>
#include <string>

namespace tuneray::testing {

std::string read_all(const std::filesystem::path& path);

// The report: every file eval writes for people (report.md, CSV, plot data, scripts and
// images), by path. Left out: the working state it resumes from (the database and the
// comparison log, whose bytes may differ after kills or between rank counts while meaning the
// same) and the temporary file of a write that a kill interrupted (hidden, never renamed over
// anything).
std::map<std::string, std::string> report_files(const std::filesystem::path& out);

// Names of the files that differ between two reports (missing on either side included).
std::string differences(const std::map<std::string, std::string>& expected,
                        const std::map<std::string, std::string>& actual);

}  // namespace tuneray::testing
