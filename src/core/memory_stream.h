// A std::istream source over bytes already in memory (a mapped file, a
// received message), without copying them as std::istringstream would.
#pragma once

#include <cstddef>
#include <streambuf>
#include <string_view>

namespace pt {

class MemoryBuffer : public std::streambuf {
 public:
  explicit MemoryBuffer(std::string_view bytes) {
    char* begin = const_cast<char*>(bytes.data());  // only ever read: the get area
    setg(begin, begin, begin + bytes.size());
  }
  // How many bytes have been read so far: where the rest begins.
  std::size_t consumed() const { return static_cast<std::size_t>(gptr() - eback()); }
};

}  // namespace pt
