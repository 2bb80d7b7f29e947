// Files are written aside and renamed over their destination once complete, so a failure or a
// kill never leaves a truncated file or destroys the previous one: the destination holds either
// its old content or the whole new one. The temporary file sits in the destination's folder
// (a rename is atomic only within one file system) and is removed when the write fails.
#pragma once

#include <fstream>
#include <functional>
#include <string>

namespace tuneray {

// Calls write(temporary path), then renames the temporary file over `path`. If `write` throws
// or the rename fails, the temporary file is removed, `path` is untouched and the error
// propagates (std::runtime_error naming `path` for the rename).
void replace_file(const std::string& path, const std::function<void(const std::string&)>& write);

// Removes from `dir` the temporary files of writes that a kill interrupted, once their process
// is gone; a live process's temporary is left alone (it may still be renamed into place).
void remove_stale_temporaries(const std::string& dir);

// replace_file for a whole text at once (reports, JSON).
void write_text_file(const std::string& path, const std::string& text);

// A text or binary output stream for `path` with the same guarantee: what is written goes to
// the temporary file; commit() checks the stream, closes it and renames; without a successful
// commit() (an exception, an early return) the destructor removes the temporary file.
class ReplacingFile {
 public:
  explicit ReplacingFile(std::string path, std::ios::openmode mode = std::ios::out);
  ~ReplacingFile();
  ReplacingFile(const ReplacingFile&) = delete;
  ReplacingFile& operator=(const ReplacingFile&) = delete;

  std::ofstream& stream() { return out_; }
  template <class T>
  ReplacingFile& operator<<(const T& value) {
    out_ << value;
    return *this;
  }
  // Throws std::runtime_error naming the file when the content could not be written in full.
  void commit();

 private:
  std::string path_, temporary_;
  std::ofstream out_;
  bool committed_ = false;
};

}  // namespace tuneray
