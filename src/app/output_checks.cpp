#include "app/output_checks.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <filesystem>
#include <system_error>

#include "app/options.h"
#include "core/file_access.h"
#include "scene/loader.h"
#include "scene/scene_description.h"

namespace fs = std::filesystem;

namespace pt {
namespace {

std::string describe(const OutputFile& f) { return f.option + " '" + f.path + "'"; }

// The file `path` names, with symbolic links, "." and ".." resolved as far as
// the path exists (an output usually does not yet).
std::string canonical(const std::string& path) {
  std::error_code ec;
  const fs::path absolute = fs::absolute(path, ec);
  if (ec) return path;
  const fs::path c = fs::weakly_canonical(absolute, ec);
  return ec ? absolute.lexically_normal().string() : c.string();
}

// The folder can take a new file: one is created beside the output (under the
// name the atomic write will use) and removed again.
std::string why_folder_refuses(const std::string& path) {
  fs::path folder = fs::path(path).parent_path();
  if (folder.empty()) folder = ".";
  struct stat st {};
  if (::stat(folder.c_str(), &st) != 0)
    return errno == ENOENT ? "the folder '" + folder.string() + "' does not exist"
                           : "the folder '" + folder.string() + "': " + std::generic_category().message(errno);
  if (!S_ISDIR(st.st_mode)) return std::string("'").append(folder.string()).append("' is not a folder");  // append: GCC 12's -Wrestrict false positive on "'" + string
  const std::string probe = path + ".tmp-probe-" + std::to_string(static_cast<long>(::getpid()));
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
  if (fd < 0) {
    if (errno == EEXIST) return {};  // a leftover of a killed run of the same id: the write replaces it
    return "cannot create a file in the folder '" + folder.string() + "': " + std::generic_category().message(errno);
  }
  ::close(fd);
  ::unlink(probe.c_str());
  return {};
}

// Every file the run reads, with what it is, as canonical paths.
std::vector<std::pair<std::string, std::string>> input_files(const Options& o, const SceneDescription& desc) {
  std::vector<std::pair<std::string, std::string>> in;
  in.emplace_back("the scene file '" + o.scene + "'", o.scene);
  const auto add_meshes = [&](const std::vector<ShapeDesc>& shapes) {
    for (const ShapeDesc& s : shapes)
      if (!s.file.empty())
        if (const auto resolved = resolve_scene_path(desc.source_path, s.file))
          in.emplace_back("the mesh '" + s.file + "' of the scene", *resolved);
  };
  add_meshes(desc.shapes);
  for (const ObjectDesc& object : desc.objects) add_meshes(object.shapes);
  for (const TextureDesc& t : desc.textures) in.emplace_back("the texture '" + t.written + "' of the scene", t.resolved);
  if (desc.render.background_image)
    in.emplace_back("the background image '" + desc.render.background_image->written + "' of the scene",
                    desc.render.background_image->resolved);
  if (desc.environment)
    in.emplace_back("the environment map '" + desc.environment->file.value + "' of the scene",
                    desc.environment->resolved);
  for (const ImportSummary& import : desc.imports)
    for (const std::string& file : import.files_read)
      in.emplace_back(std::string("'").append(fs::path(file).filename().string()) + "', which the import of '" +
                          import.file + "' reads",
                      file);  // append: GCC 12's -Wrestrict false positive on "'" + string
  if (!o.ocio_config.empty()) in.emplace_back("--ocio-config '" + o.ocio_config + "'", o.ocio_config);
  for (auto& [what, path] : in) path = canonical(path);
  return in;
}

}  // namespace

std::vector<OutputFile> output_files(const Options& o) {
  std::vector<OutputFile> files;
  if (o.replaying()) return files;
  for (const std::string& path : o.outputs) files.push_back({"-o", path});
  if (!o.checkpoint.empty()) files.push_back({"--checkpoint", o.checkpoint});
  if (!o.shard_out.empty()) files.push_back({"--shard-out", o.shard_out});
  if (!o.report.empty()) files.push_back({"--report", o.report});
  return files;
}

bool check_output_files(const std::vector<OutputFile>& outputs, std::string& error) {
  std::map<std::string, const OutputFile*> seen;
  for (const OutputFile& f : outputs) {
    std::string why = special_file_kind(f.path);
    if (!why.empty()) why += " (outputs replace a regular file whole)";
    if (why.empty()) why = why_folder_refuses(f.path);
    if (!why.empty()) {
      error = "cannot write " + describe(f) + ": " + why;
      return false;
    }
    const auto [it, inserted] = seen.emplace(canonical(f.path), &f);
    if (!inserted) {
      error = describe(f) + (it->second->path == f.path && it->second->option == f.option
                                 ? " is given more than once"
                                 : " is the same file as " + describe(*it->second)) +
              "; each output needs a file of its own";
      return false;
    }
  }
  return true;
}

bool check_outputs_are_not_inputs(const Options& o, const std::vector<OutputFile>& outputs,
                                  const SceneDescription& desc, std::string& error) {
  const std::vector<std::pair<std::string, std::string>> inputs = input_files(o, desc);
  const std::string resume = o.resume.empty() ? std::string() : canonical(o.resume);
  for (const OutputFile& f : outputs) {
    const std::string c = canonical(f.path);
    for (const auto& [what, path] : inputs)
      if (c == path) {
        error = "refusing to write " + describe(f) + ": it is " + what + ", which this run reads";
        return false;
      }
    if (c == resume && f.option != "--checkpoint") {
      error = "refusing to write " + describe(f) + ": it is --resume's checkpoint '" + o.resume +
              "' (only --checkpoint may name it, to go on from it)";
      return false;
    }
  }
  return true;
}

FileStamp file_stamp(const std::string& path) {
  FileStamp s;
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return s;
  s.exists = true;
  s.device = st.st_dev;
  s.inode = st.st_ino;
  s.size = static_cast<int64_t>(st.st_size);
  s.mtime_ns = static_cast<int64_t>(st.st_mtim.tv_sec) * 1000000000 + st.st_mtim.tv_nsec;
  return s;
}

void OutputStamps::take(const std::vector<OutputFile>& outputs) {
  for (const OutputFile& f : outputs) stamps_[f.path] = file_stamp(f.path);
}

bool OutputStamps::unchanged(const std::string& path) const {
  const auto it = stamps_.find(path);
  return it == stamps_.end() || it->second == file_stamp(path);
}

void OutputStamps::wrote(const std::string& path) { stamps_[path] = file_stamp(path); }

std::string conflict_path(const std::string& path) {
  const fs::path p(path);
  fs::path name = p.stem();
  name += ".conflict-" + std::to_string(static_cast<long>(::getpid()));
  name += p.extension();
  return (p.parent_path() / name).string();
}

bool write_guarded(const std::string& path, OutputStamps& stamps,
                   const std::function<bool(const std::string& path, std::string& error)>& write, std::string& error) {
  if (stamps.unchanged(path)) {
    if (!write(path, error)) return false;
    stamps.wrote(path);
    return true;
  }
  const std::string kept = conflict_path(path);
  if (!write(kept, error)) return false;
  error = "'" + path + "' was changed by another program while this run went on (another render writing the " +
          "same name?); it was not replaced, and this run's file is '" + kept + "'";
  return false;
}

}  // namespace pt
