// A file mapped read-only into memory (mmap), for reading large files without
// copying them: the merge of shards reads gigabytes of film state once
// (docs/distributed.md, "The merge").
//
// The mapping shows the file as it was when mapped only as long as nobody
// truncates it in place: the pages of a file shortened while mapped cannot be
// read (the process would get SIGBUS). The files mapped here (shard files) are
// written atomically, by renaming a finished temporary file over the old one,
// which leaves an existing mapping intact.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace pt {

class MappedFile {
 public:
  // Maps `path`; std::nullopt with `error` (the system's words) when it cannot
  // be opened, is no regular file or cannot be mapped. An empty file maps to
  // no bytes.
  static std::optional<MappedFile> open(const std::string& path, std::string& error);
  MappedFile(MappedFile&& other) noexcept;
  MappedFile& operator=(MappedFile&& other) noexcept;
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;
  ~MappedFile();

  std::string_view bytes() const { return {static_cast<const char*>(data_), size_}; }

 private:
  MappedFile(void* data, std::size_t size) : data_(data), size_(size) {}
  void* data_ = nullptr;
  std::size_t size_ = 0;
};

}  // namespace pt
