// Every file a run writes (the images, the checkpoint, the run record),
// checked before anything is rendered, so that no render is lost to a path
// that could never be written (docs/cli.md, "Outputs"). Library code: the
// checks return their message, naming the path as the user gave it.
#pragma once

#include <sys/types.h>

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

namespace pt {

struct Options;
struct SceneDescription;

struct OutputFile {
  std::string option;  // "-o", "--checkpoint", "--shard-out" or "--report"
  std::string path;    // as given
};

// The files the run will write: each -o, the checkpoint, a shard's state
// (--shard-out) and the run record (none for a replay, which writes nothing).
std::vector<OutputFile> output_files(const Options& o);

// Before the scene is read: each output's folder exists and can take a new
// file (a file is created there and removed again, so permissions, read-only
// file systems and the like all show), an existing output is a regular file,
// and no two outputs are one file (compared as canonical paths: symbolic
// links, "./" and "../" resolved). False with `error`.
bool check_output_files(const std::vector<OutputFile>& outputs, std::string& error);

// After the scene is read: no output is one of the run's inputs: the scene
// file, the meshes, textures and images it names, --ocio-config, or --resume's
// checkpoint (which only --checkpoint may name: it then goes on from it).
bool check_outputs_are_not_inputs(const Options& o, const std::vector<OutputFile>& outputs,
                                  const SceneDescription& desc, std::string& error);

// What a file is at a moment: whether it exists and its device, inode, size and
// modification time (a replaced file has a new inode, a rewritten one a new
// time or size).
struct FileStamp {
  bool exists = false;
  dev_t device = 0;
  ino_t inode = 0;
  int64_t size = 0;
  int64_t mtime_ns = 0;
  bool operator==(const FileStamp& o) const {
    return exists == o.exists && device == o.device && inode == o.inode && size == o.size && mtime_ns == o.mtime_ns;
  }
};
FileStamp file_stamp(const std::string& path);

// Two runs writing the same names in one folder: each output's stamp when the
// run started, so that a file another program wrote since is not replaced
// (checked just before each write; a file replaced during that write itself
// goes unnoticed).
class OutputStamps {
 public:
  void take(const std::vector<OutputFile>& outputs);
  // True if `path` is as it was when the stamps were taken, or as this run
  // last wrote it (wrote()); true for a path never stamped.
  bool unchanged(const std::string& path) const;
  void wrote(const std::string& path);

 private:
  std::map<std::string, FileStamp> stamps_;
};

// Where a run keeps an output it must not write over: "out/a.exr" ->
// "out/a.conflict-<pid>.exr".
std::string conflict_path(const std::string& path);

// Writes `path` with `write(path, error)` unless another program changed it
// since `stamps` were taken: then the content goes to conflict_path(path)
// instead and the result is false with an error saying so. Records the new
// stamp after a write of its own.
bool write_guarded(const std::string& path, OutputStamps& stamps,
                   const std::function<bool(const std::string& path, std::string& error)>& write, std::string& error);

}  // namespace pt
