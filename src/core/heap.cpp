#include "core/heap.h"

#include <cstdlib>  // defines __GLIBC__ on glibc

#if defined(__GLIBC__)
#include <malloc.h>
#endif
#if defined(__linux__)
#include <link.h>
#include <sys/mman.h>
#include <unistd.h>
#endif

#include <algorithm>
#include <cstdint>

namespace pt {

void release_free_heap() {
#if defined(__GLIBC__)
  malloc_trim(0);
#endif
}

#if defined(__linux__)
namespace {

struct Release {
  std::initializer_list<std::string_view> names;
  std::size_t bytes = 0;
};

bool has_text_relocations(const dl_phdr_info& info) {
  for (int i = 0; i < info.dlpi_phnum; ++i) {
    if (info.dlpi_phdr[i].p_type != PT_DYNAMIC) continue;
    const auto* dyn = reinterpret_cast<const ElfW(Dyn)*>(info.dlpi_addr + info.dlpi_phdr[i].p_vaddr);
    for (; dyn->d_tag != DT_NULL; ++dyn) {
      if (dyn->d_tag == DT_TEXTREL || (dyn->d_tag == DT_FLAGS && (dyn->d_un.d_val & DF_TEXTREL) != 0)) return true;
    }
  }
  return false;
}

// [begin, end) less the RELRO range: the pages strictly before and after it.
void advise(uintptr_t begin, uintptr_t end, uintptr_t relro_begin, uintptr_t relro_end, std::size_t& bytes) {
  const auto page = static_cast<uintptr_t>(sysconf(_SC_PAGESIZE));
  const auto drop = [&](uintptr_t b, uintptr_t e) {
    b = (b + page - 1) & ~(page - 1);  // whole pages inside the range only
    e &= ~(page - 1);
    if (b < e && madvise(reinterpret_cast<void*>(b), e - b, MADV_DONTNEED) == 0) bytes += e - b;
  };
  if (relro_end <= begin || relro_begin >= end) return drop(begin, end);
  drop(begin, relro_begin);
  drop(relro_end, end);
}

int release_object(dl_phdr_info* info, std::size_t /*size*/, void* data) {
  auto* r = static_cast<Release*>(data);
  const std::string_view path = info->dlpi_name != nullptr ? info->dlpi_name : "";
  const std::string_view file = path.substr(std::min(path.size(), path.rfind('/') + 1));
  if (file.empty() || std::none_of(r->names.begin(), r->names.end(),
                                   [&](std::string_view n) { return file.find(n) != std::string_view::npos; }))
    return 0;
  if (has_text_relocations(*info)) return 0;
  uintptr_t relro_begin = 0, relro_end = 0;
  for (int i = 0; i < info->dlpi_phnum; ++i) {
    const ElfW(Phdr)& ph = info->dlpi_phdr[i];
    if (ph.p_type == PT_GNU_RELRO) {
      relro_begin = info->dlpi_addr + ph.p_vaddr;
      relro_end = relro_begin + ph.p_memsz;
    }
  }
  for (int i = 0; i < info->dlpi_phnum; ++i) {
    const ElfW(Phdr)& ph = info->dlpi_phdr[i];
    if (ph.p_type != PT_LOAD || (ph.p_flags & PF_W) != 0) continue;
    const uintptr_t begin = info->dlpi_addr + ph.p_vaddr;
    advise(begin, begin + ph.p_filesz, relro_begin, relro_end, r->bytes);
  }
  return 0;
}

}  // namespace
#endif

std::size_t release_library_pages(std::initializer_list<std::string_view> names) {
#if defined(__linux__)
  Release r{names};
  dl_iterate_phdr(&release_object, &r);
  return r.bytes;
#else
  (void)names;
  return 0;
#endif
}

}  // namespace pt
