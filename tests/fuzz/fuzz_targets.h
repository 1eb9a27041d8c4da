// The fuzzing harnesses' entry points, one per file parser. Each takes any
// bytes, runs the parser the way the renderer does, and checks what must hold
// for every input: a failure reports an error (with a location where the
// parser has one), a success yields data the rest of the renderer can trust
// (indices in range, finite values, consistent sizes). A broken invariant
// aborts with a message, which libFuzzer records as a crash.
//
// They are linked into the libFuzzer executables (PT_FUZZ=ON, tools/dev/fuzz.sh)
// and into the ordinary test suite, which replays the seed corpora and every
// crash ever found (tests/hostile/fuzz-regressions/<harness>/) through them.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace pt::fuzz {

// A scene file of any family (native, Path of Light, CGR), through
// load_scene_from_string, in normal and in strict mode. Relative mesh and
// texture paths resolve against tests/fuzz/fixtures (mesh.ply, mesh.obj,
// texture.png exist there).
int scene_one_input(const uint8_t* data, std::size_t size);

// A PLY file, through parse_ply.
int ply_one_input(const uint8_t* data, std::size_t size);

// A Wavefront OBJ file, through load_obj (it reads files: the bytes are
// written to a temporary file first).
int obj_one_input(const uint8_t* data, std::size_t size);

// A film state (the film part of a --checkpoint file), through Film::read_state
// into films of the seeds' shapes; an accepted state must be written back
// byte for byte, a refused one must leave the film unchanged.
int film_state_one_input(const uint8_t* data, std::size_t size);

// A whole checkpoint file (--checkpoint, --resume: the header line and the
// film state; src/app/checkpoint.h): the header alone, then the whole file
// into films of the seeds' shapes. A refusal names the file and leaves the
// film unchanged; an accepted checkpoint has a header of valid types and
// ranges, no pixel with more samples than spp_done, and reads back unchanged
// once written.
int checkpoint_one_input(const uint8_t* data, std::size_t size);

// A shard file (--shard-out, `pathtracer merge`; src/app/shard_file.h): the
// header, then, for crops of at most 2^16 pixels, the film state. A refusal
// names the file; an accepted shard has a header of valid types and ranges
// (pieces inside the frame and the target), reads back unchanged once
// written, and goes through a merge of it alone.
int shard_one_input(const uint8_t* data, std::size_t size);

struct Harness {
  const char* name;  // also the folder name of its regression cases
  int (*run)(const uint8_t* data, std::size_t size);
};

// Every harness, for the regression test and tools/dev/fuzz.sh.
std::vector<Harness> harnesses();

}  // namespace pt::fuzz
