#pragma once
// Write-then-rename: a file appears under its final name complete or not at all.
#include <string>

namespace dicsynth {

class AtomicFile {
 public:
  // `finalPath`'s folder must exist. The temporary file lives in the same folder (same filesystem,
  // so the rename is atomic) and keeps the extension, so format detection by extension still works.
  explicit AtomicFile(std::string finalPath);
  ~AtomicFile();  // removes the temporary file unless commit() succeeded
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  const std::string& tempPath() const { return temp_; }
  const std::string& finalPath() const { return final_; }
  void commit();  // rename temp → final; throws Error on failure

 private:
  std::string final_, temp_;
  bool committed_ = false;
};

}  // namespace dicsynth
