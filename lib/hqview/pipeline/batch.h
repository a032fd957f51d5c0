#pragma once
// `hqview batch`: analyse a collection of meshes (a directory tree or a
// manifest) into one bundle per mesh plus an index (batch_index.h). One mesh
// is one independent job: meshes run in parallel within a memory budget, a
// failing mesh is recorded with its error and the others go on. `--shard I/N`
// takes a stable, path-based part of the collection (ARCHITECTURE.md,
// "Scaling out"); `--resume` keeps a bundle whose input hash and HQView
// version are unchanged. The library never prints: progress goes to a
// BatchProgress sink that main() implements.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "hqview/pipeline/analyze.h"
#include "hqview/report/batch_index.h"
#include "hqview/report/single_file.h"

namespace hq {

// One row of the collection.
struct BatchInput {
  std::string path;                      // index key and bundle directory: relative, '/'-separated
  std::filesystem::path mesh_file;       // the file to open
  std::filesystem::path reference_file;  // --reference for this mesh; empty: none
  std::filesystem::path compare_file;    // --compare for this mesh (MESH2); empty: none
  std::string label;                     // method / algorithm, for the per-method comparison
  std::string model;                     // model name (rows of the method comparison); default: model_of_path
  std::string variant;                   // which mesh of the model and method; default: model_of_path
  std::string up;                        // the manifest's up axis ("+y"; parse_up_axis) or "auto"; empty: the run's --up
  PaperInfo paper;                       // the method's paper (HexaLab's index.json)
  std::string skip_reason;               // not empty: listed but not analysed (not a hex mesh)
};

// The model and variant a mesh path stands for, when the manifest does not
// say (docs/batch.md, "Models and variants"): the file stem, lower-cased;
// a hex marker ("_hex", "-hex", ".hex") ends the model, what follows it is
// the variant ("kiss_hex_coarse" -> kiss, coarse); else trailing variant
// suffixes ("_in", "_out", "_padded", "_opt", "_graded", "_coarse", "_fine",
// "_final", "_<digits>", also with '-') move to the variant ("cat_2_padded"
// -> cat, 2_padded); a stem left empty or generic ("hex", "mesh", "model",
// "polycube", "volume", "output", "result", "input") names no model: the
// parent folder does, and the whole stem is the variant ("asm/polycube_in"
// -> asm, polycube_in; "anc101/hex" -> anc101, "").
struct ModelAndVariant {
  std::string model, variant;
};
ModelAndVariant model_of_path(const std::filesystem::path& mesh);

// HexaLab's datasets/index.json as it is published: {"sources": [{"paper":
// {title, year, DOI, ...}, "path": folder, "label": method, "data": [mesh
// paths relative to the folder]}]}; a trailing comma before } or ] is
// accepted here (the published file has one), nowhere else. Files that are
// not hex meshes become skipped rows. Throws ParseError naming the source.
std::vector<BatchInput> parse_hexalab_index(const nlohmann::json& index, const std::string& name,
                                            const std::filesystem::path& base_dir);
// The text without commas that directly precede (blanks between) a } or ]
// outside strings: JSON with trailing commas made strict.
std::string strip_trailing_commas(std::string_view text);

// True for the hex mesh extensions read_hex_mesh() knows (.mesh .vtk .vtu
// .msh .ovm .inp .e .exo; any case).
bool is_hex_mesh_extension(const std::filesystem::path& path);

// Every mesh file under `dir` (recursive), sorted by relative path: the
// volume formats, and the polygon formats (.obj .off .ply: surface meshes)
// in folders that hold no volume-format file (beside volume meshes they are
// reference surfaces: listed with a skip_reason, not analysed); hidden entries and HQView outputs
// (directories with report.json or index.json) are skipped.
// Throws InputError when `dir` cannot be listed.
std::vector<BatchInput> collect_directory(const std::filesystem::path& dir);

// A manifest: CSV with a header row naming the columns (mesh, reference,
// compare, label or method, model, variant, up; only mesh is required), or JSON
// (an array of objects with those keys, or of strings, or HexaLab's index). Relative file names are
// relative to the manifest's directory; rows keep the manifest's order until
// the index sorts them. Throws ParseError (`path:line: what`) on a malformed
// row or a duplicate mesh.
std::vector<BatchInput> read_manifest(const std::filesystem::path& file);
std::vector<BatchInput> parse_manifest(std::string_view text, const std::string& name,
                                       const std::filesystem::path& base_dir, bool is_json);

// A directory or a manifest file (.csv, .json).
std::vector<BatchInput> collect_batch_inputs(const std::filesystem::path& dir_or_manifest);

// Shard I of N, 1 <= I <= N (`--shard I/N`).
struct Shard {
  int index = 1;
  int count = 1;
};

// The shard (1-based) that owns `path`: a hash of the path alone, so the
// partition does not change when other meshes are added or removed.
int shard_of(std::string_view path, int count);
std::vector<BatchInput> select_shard(const std::vector<BatchInput>& inputs, const Shard& shard);

// Makes the renderer one mesh's views are drawn with (one per mesh: meshes
// run on several threads at once).
using RendererFactory = std::function<std::unique_ptr<Renderer>()>;

struct BatchOptions {
  AnalyzeOptions analyze;         // template: mesh_path and reference_path are set per mesh
  RendererFactory make_renderer;  // empty: no views
  std::filesystem::path output;
  int jobs = 1;                     // meshes analysed at once
  std::uint64_t memory_budget = 0;  // bytes for the meshes in flight (estimated); 0: no limit
  bool resume = false;
  bool force = false;         // passed to each bundle (replace a non-bundle directory)
  double mesh_timeout = 0;    // seconds per mesh (--mesh-timeout); 0: none. Over it: failed, the batch goes on
  std::string link_base;      // --link-base, normalized; each bundle's pages link under link_base + its path
  SingleFile single_file = SingleFile::none;  // --single-file: report.html in each bundle and OUT/report.html
};

// Progress sink (main draws a bar or prints lines). Called from worker
// threads, one call at a time.
class BatchProgress {
 public:
  virtual ~BatchProgress() = default;
  virtual void mesh_started(const BatchInput& /*input*/) {}
  virtual void mesh_finished(const BatchEntry& /*entry*/, bool /*is_resumed*/, double /*seconds*/, int /*done*/,
                             int /*total*/) {}
};

// Analyses every input into options.output / input.path (bundle_path()).
// Never throws for a mesh's failure (it is recorded in its entry); throws
// ValueError when options.output is unusable, Interrupted when a stop was
// requested (stop.h: the meshes running stop, no other starts, bundles
// already written stay). Entries sorted by path.
std::vector<BatchEntry> run_batch(const std::vector<BatchInput>& inputs, const BatchOptions& options,
                                  BatchProgress* progress);

// One mesh: analyze + gates + bundle writing, or the kept bundle with
// --resume. `is_resumed` tells which.
BatchEntry run_batch_mesh(const BatchInput& input, const BatchOptions& options, bool& is_resumed);

// `hqview merge`: copies every shard's bundles into `out` and returns the
// union of their index entries, sorted by path. Throws InputError for a
// shard without index.json or a mesh present in two shards.
std::vector<BatchEntry> merge_shards(const std::vector<std::filesystem::path>& shard_dirs,
                                     const std::filesystem::path& out);

}  // namespace hq
