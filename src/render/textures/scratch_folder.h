// Files a render scene writes for itself: a model file's embedded images
// (a .glb buffer view, a data: URI), which the texture cache reads as files
// so that they are filtered, MIP-mapped and cut out (their alpha channel)
// exactly as the same images beside the model are (docs/importing.md). A
// private folder (mode 0700) under $TMPDIR, created on the first write and
// removed with everything in it when the owner is destroyed.
#pragma once

#include <string>
#include <vector>

namespace pt {

class ScratchFolder {
 public:
  ScratchFolder() = default;
  ~ScratchFolder();
  ScratchFolder(const ScratchFolder&) = delete;
  ScratchFolder& operator=(const ScratchFolder&) = delete;

  // Writes `bytes` to a new file whose name ends in `.extension`; returns its
  // path, or an empty string with `error` filled.
  std::string write(const std::vector<unsigned char>& bytes, const std::string& extension, std::string& error);
  const std::string& path() const { return path_; }

 private:
  std::string path_;  // empty until the first write
  int files_ = 0;
};

}  // namespace pt
