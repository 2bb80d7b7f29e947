#include "report_files.h"

#include <fstream>
#include <iterator>

namespace tuneray::testing {

namespace fs = std::filesystem;

std::string read_all(const fs::path& path) {
  std::ifstream f(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}

std::map<std::string, std::string> report_files(const fs::path& out) {
  std::map<std::string, std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(out)) {
    if (!entry.is_regular_file()) continue;
    const std::string name = entry.path().filename().string();
    if (name.rfind("eval.db", 0) == 0 || name == "comparisons.tsv" ||
        name.find(".partial-") != std::string::npos)
      continue;
    files[fs::relative(entry.path(), out).string()] = read_all(entry.path());
  }
  return files;
}

std::string differences(const std::map<std::string, std::string>& expected,
                        const std::map<std::string, std::string>& actual) {
  std::string names;
  for (const auto& [name, bytes] : expected) {
    auto it = actual.find(name);
    if (it == actual.end() || it->second != bytes) names += " " + name;
  }
  for (const auto& [name, bytes] : actual)
    if (!expected.count(name)) names += " " + name + "(extra)";
  return names;
}

}  // namespace tuneray::testing
