#include "imagelib/image_library.h"

#include <dlfcn.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <mutex>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <system_error>

namespace pt {

namespace {

namespace fs = std::filesystem;

constexpr const char* kModuleName = "pt_oiio.so";
constexpr const char* kModuleEnv = "PT_OIIO_MODULE";

struct Candidate {
  std::string path;
  std::string origin;  // why this path is tried
};

// The directory of the running executable ("" if /proc is not there).
std::string executable_dir() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  return ec ? std::string() : exe.parent_path().string();
}

std::vector<Candidate> candidates() {
  if (const char* env = std::getenv(kModuleEnv); env != nullptr && *env != '\0')
    return {{env, std::string("set by $") + kModuleEnv}};
  std::vector<Candidate> list;
  if (const std::string dir = executable_dir(); !dir.empty())
    list.push_back({dir + "/" + kModuleName, "beside the executable"});
#ifdef PT_OIIO_MODULE_BUILD_PATH
  if (list.empty() || list.front().path != PT_OIIO_MODULE_BUILD_PATH)
    list.push_back({PT_OIIO_MODULE_BUILD_PATH, "in the build tree"});
#endif
  return list;
}

bool exists(const std::string& path) {
  std::error_code ec;
  return fs::exists(path, ec);
}

struct Loaded {
  const ImageLibrary* library = nullptr;
  std::string error;
};

// dlopen with RTLD_LOCAL: nothing of OpenImageIO's leaks into the program's
// symbol namespace. The module is never closed (its objects live as long as
// the process).
Loaded load() {
  const std::vector<Candidate> list = candidates();
  std::string tried;
  for (const Candidate& c : list) {
    if (!exists(c.path) && list.size() > 1) {
      tried += (tried.empty() ? "" : ", ") + c.path + " (" + c.origin + ")";
      continue;
    }
    const std::string what = "the image module '" + c.path + "' (" + c.origin + ")";
    void* handle = ::dlopen(c.path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (handle == nullptr) {
      const char* why = ::dlerror();
      return {nullptr, "cannot load " + what + ": " + (why != nullptr ? why : "unknown error")};
    }
    using AbiFn = const char* (*)();
    using LibraryFn = const ImageLibrary* (*)();
    const auto abi = reinterpret_cast<AbiFn>(::dlsym(handle, "pt_image_library_abi"));
    const auto get = reinterpret_cast<LibraryFn>(::dlsym(handle, "pt_image_library"));
    if (abi == nullptr || get == nullptr)
      return {nullptr, "cannot use " + what + ": it is not a pathtracer image module (no pt_image_library)"};
    if (const std::string theirs = abi(); theirs != image_library_abi())
      return {nullptr, "cannot use " + what + ": it was built as '" + theirs + "', this program needs '" +
                           image_library_abi() + "' (rebuild the pt_oiio target)"};
    const ImageLibrary* library = get();
    if (library == nullptr) return {nullptr, "cannot use " + what + ": it returned no library"};
    return {library, {}};
  }
  return {nullptr, "cannot load the image module " + std::string(kModuleName) + ": not found at " + tried +
                       " (set $" + kModuleEnv + " to its path)"};
}

// The one piece of global state of the image library: the module, loaded
// once (std::call_once: thread-safe), never unloaded.
struct State {
  std::once_flag once;
  std::atomic<const ImageLibrary*> library{nullptr};
  std::string error;
};

State& state() {
  static State s;
  return s;
}

}  // namespace

const ImageLibrary* image_library(std::string& error) {
  State& s = state();
  std::call_once(s.once, [&s] {
    Loaded l = load();
    s.error = std::move(l.error);
    s.library.store(l.library, std::memory_order_release);
  });
  const ImageLibrary* library = s.library.load(std::memory_order_acquire);
  if (library == nullptr) error = s.error;
  return library;
}

const ImageLibrary* loaded_image_library() { return state().library.load(std::memory_order_acquire); }

std::string image_module_path(std::string* origin) {
  const std::vector<Candidate> list = candidates();
  for (const Candidate& c : list)
    if (exists(c.path)) {
      if (origin != nullptr) *origin = c.origin;
      return c.path;
    }
  if (list.empty()) return kModuleName;
  if (origin != nullptr) *origin = list.front().origin + ", missing";
  return list.front().path;
}

}  // namespace pt
