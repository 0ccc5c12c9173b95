#pragma once
//! \file
//! `pdeface compare`: how small a face scan can be and what it costs, side by side — the scan as raw mesh
//! files (and gzipped), Draco at every quantisation, decimation + Draco at byte budgets, and the PDE
//! `.pdef` at sampling ratios — each measured on what decoding its bytes gives back.

#include "pdeface/core/file.hpp"
#include "pdeface/core/mesh.hpp"
#include "pdeface/core/result.hpp"
#include "pdeface/metrics/colour.hpp"
#include "pdeface/metrics/fidelity.hpp"
#include "pdeface/pde/surface.hpp"
#include "pdeface/pipeline/encode.hpp"

#include <cstddef>
#include <filesystem>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace pdeface::pipeline {

//! The families of variants, one series each in the plot.
//! `DracoColour`: Draco with the scan's texture coordinates (or vertex colours) and its photograph beside
//! it; `PdeTexture`: the `.pdef` with a texture layer. Both are measured on colour too.
enum class Method { Raw, Gzip, Draco, DecimateDraco, Pde, DracoColour, PdeTexture };
[[nodiscard]] std::string_view to_string(Method method) noexcept;

struct CompareOptions {
  //! Draco: position quantisation bits, one variant each (8–16 by default).
  std::vector<int> draco_bits{8, 9, 10, 11, 12, 13, 14, 15, 16};
  int draco_level = 7; //!< Draco compression level for the Draco and decimate + Draco variants (0–10)
  //! Decimate + Draco: byte budgets (and one at each `.pdef` variant's size when `budgets_at_pde`).
  std::vector<std::size_t> budgets{1024, 2048, 4096, 8192, 16384, 32768};
  bool budgets_at_pde = true;
  //! The quantisation bits tried for each budget; the one with the least error is kept.
  std::vector<int> decimate_bits{8, 9, 10, 11, 12, 13, 14};
  //! A decimated row's bytes land in [budget × (1 − `budget_slack`), budget].
  double budget_slack = 0.1;
  bool lock_border = false; //!< meshoptimizer keeps the scan's outline (costs triangles at small budgets)
  //! PDE: sampling ratios (5–60 %), each lossy and lossless (`pde_lossless`, `pde_lossy`), scheme.
  std::vector<double> ratios{0.05, 0.10, 0.20, 0.30, 0.60};
  bool pde_lossy = true;
  bool pde_lossless = true;
  //! PDE with a residual layer (`.pdef` version 3, `pdeface encode --size`): the curves at
  //! `pde_budget_ratio` (as `pdeface encode --size` puts them), the file at each of these sizes (the
  //! decimate + Draco budgets by default).
  std::vector<std::size_t> pde_budgets{1024, 2048, 4096, 8192, 16384, 32768};
  double pde_budget_ratio = kResidualRatio;
  pde::Scheme scheme = pde::Scheme::Spline;
  int gzip_level = 6; //!< zlib level of the gzipped raw files (gzip's default)
  //! Compress only the face (`align::crop_face`: the face's height, the cheeks, no ears, neck, shoulders or
  //! pedestal), the part of the scan a `.pdef` holds, instead of the whole file. Fairer for busts and heads,
  //! where the mesh codecs otherwise spend their bytes on what the face mask does not judge.
  bool crop_face = false;
  metrics::FidelityOptions fidelity;
  //! A `.pdef` row whose decoded surface fails this check (`self_check` on the face mask) is a failed row
  //! with the reason, as `pdeface encode` would refuse to write the file.
  metrics::CheckLimits check;
  //! Heat maps: the error (mesh → scan, mm) coloured from 0 (blue) to this (red) on the GLBs written.
  double heat_max_mm = 1.0;
  double heat_ratio =
      0.10; //!< the PDE variant shown as a heat map (lossy), with decimate + Draco at its size
  int heat_draco_bits = 11; //!< and Draco at these bits
  bool keep_bytes = false;  //!< keep every variant's encoded bytes (`Variant::encoded`) to write them
  //! Colour, where the scan has it (a photograph with texture coordinates, or vertex colours): Draco at
  //! `colour_draco_bits` with the texture coordinates at `draco_uv_bits` (or the colours at
  //! `draco_color_bits`) beside the photograph at each of `photo_scales` (1: the scan's own image file;
  //! smaller: resized and encoded as JPEG at `photo_quality`), and the `.pdef` at `texture_ratio` with a
  //! texture layer at each of `textures`; each measured on the colours of the face mask (PSNR, ΔE₀₀), and
  //! written as a textured GLB beside the heat maps.
  bool colour = true;
  int colour_draco_bits = 11;
  int draco_uv_bits = 12;
  int draco_color_bits = 8;
  double texture_ratio = default_ratio({}); //!< as `pdeface encode --texture` puts the curves
  std::vector<double> photo_scales{1.0, 0.5, 0.25};
  int photo_quality = 80;
  struct Texture {
    double texel_mm = 0.5;
    int quality = 80;
  };
  std::vector<Texture> textures{{0.5, 80}, {0.5, 50}, {1.0, 80}, {1.0, 50}};
  double colour_spacing_mm = 1.0; //!< the colour measure's sample spacing on the scan's face
  //! Threads per scan (0: the machine's cores); `compare_scans` shares the cores between the scans.
  unsigned threads = 0;
};

//! One encoding of one scan, measured on its decoded bytes.
struct Variant {
  Method method = Method::Raw;
  std::string name;          //!< "ply", "ply.gz", "draco 11 bits", "decimate+draco 2048 B", "pde 10 % lossy"
  std::string extension;     //!< of its file: ".ply", ".ply.gz", ".drc", ".pdef"
  int bits = 0;              //!< Draco and decimate + Draco: position quantisation bits
  std::size_t budget = 0;    //!< decimate + Draco, PDE with a residual layer: the byte budget
  double ratio = 0.0;        //!< PDE: the sampling ratio
  bool lossless = true;      //!< raw (float32) and lossless PDE
  std::size_t bytes = 0;     //!< of the encoded file
  double ratio_to_ply = 0.0; //!< bytes / the raw binary PLY's bytes
  double encode_ms = 0.0;    //!< decimate + Draco: simplification and encoding of the row's mesh
  double decode_ms = 0.0;    //!< parsing the bytes back into a mesh (PDE: and solving the surface)
  std::size_t vertices = 0;  //!< of the decoded mesh
  std::size_t triangles = 0;
  std::optional<metrics::MeshFidelity> fidelity; //!< measured on the decoded mesh (canonical frame, mm)
  //! Colour rows: of `bytes`, the image's (the photograph or the texture layer's JPEG) and the colour
  //! attributes' (Draco: its bytes over the same mesh's without them)
  std::size_t image_bytes = 0;
  std::size_t attribute_bytes = 0;
  std::optional<metrics::ColourError> colour; //!< the face mask's colours against the scan's
  std::string failure;                        //!< why there is no fidelity
  std::string encoded;                        //!< the bytes, when `CompareOptions::keep_bytes`
};

//! A heat-map GLB of one variant: its decoded mesh in the canonical frame (mm), every vertex coloured by
//! its distance to the scan (0 blue … `scale_mm` red; grey outside the face mask, where nothing is judged).
struct HeatMap {
  std::string variant;   //!< `Variant::name`
  std::string file;      //!< file name in the report folder
  std::string glb;       //!< the bytes
  std::string front_svg; //!< an SVG `<image>` of it from the front, for the page (mm user units)
  double scale_mm = 1.0;
};

//! A colour variant's decoded mesh with its image, as a GLB (canonical frame, mm).
struct TexturedGlb {
  std::string variant; //!< `Variant::name`
  std::string file;    //!< file name in the report folder
  std::string glb;     //!< the bytes
};

//! One scan: its variants, or why it could not be compared.
struct ScanReport {
  std::string name;   //!< file name (the built-in sample: "sample face")
  std::string source; //!< as given
  Units units = Units::Unknown;
  double units_per_mm = 1.0;               //!< to state distances in the scan's units
  std::size_t vertices = 0, triangles = 0; //!< of what was compressed (the face alone with `crop_face`)
  bool face_only = false;                  //!< `CompareOptions::crop_face`
  std::size_t ply_bytes = 0;               //!< the raw binary PLY every ratio refers to
  std::vector<Variant> variants;
  std::vector<HeatMap> heat_maps;
  std::vector<TexturedGlb> textured;                          //!< the colour variants' GLBs
  metrics::ColourSource colour = metrics::ColourSource::None; //!< what colour the scan has
  std::string failure; //!< unreadable, no face ...: the scan has no variants
  double seconds = 0.0;
};

//! What happened to the scan a progress event is about.
enum class ProgressEvent {
  Step,   //!< a step finished (`Progress::step`: "aligned", "draco 11 bits", ...)
  Done,   //!< the scan is compared (`Progress::seconds`)
  Failed, //!< the scan could not be compared (`Progress::failure`)
};

//! Where a batch is (`compare_scans` reports through a callback; drawing it is the caller's business).
struct Progress {
  std::size_t steps_done = 0, steps_total = 0; //!< variants measured, over every scan
  std::size_t scans_done = 0, scans_total = 0, scans_failed = 0;
  std::string scan; //!< the scan the event is about
  ProgressEvent event = ProgressEvent::Step;
  std::string step;     //!< Step: the step that finished
  double seconds = 0.0; //!< Done: the time the scan took
  std::string failure;  //!< Failed: why (`Error::to_string`, naming the scan's file)
  //! The event in words: the step, "done in 8.6 s" or "failed: <failure>".
  [[nodiscard]] std::string what() const;
};
using ProgressCallback = std::function<void(const Progress&)>;

//! Every variant of one scan (any frame and units), named `name`. Errors: the scan has no face (alignment,
//! slicing or the face mask fail), named `name`. A variant that fails is a row with `failure`.
[[nodiscard]] Result<ScanReport> compare_scan(const Mesh& scan, std::string_view name,
                                              const CompareOptions& options = {},
                                              const std::function<void(std::string_view)>& step = {});

//! Where the scans of a batch come from: files (folders expanded to the mesh files in them, sorted) or,
//! when none is given, the built-in sample face.
struct CompareRequest {
  std::vector<std::filesystem::path> inputs;
  CompareOptions options;
  ProgressCallback progress; //!< called from worker threads, one call at a time
};

struct Report {
  std::vector<ScanReport> scans; //!< in the order given; failed ones carry `failure`
  CompareOptions options;
  double seconds = 0.0;
  [[nodiscard]] std::size_t failed() const;
};

//! The inputs as scan files: each folder replaced by the mesh files in it (by extension), sorted.
//! Errors: `Io` for a path that is neither a file nor a folder.
[[nodiscard]] Result<std::vector<std::filesystem::path>>
expand_inputs(std::span<const std::filesystem::path> inputs);

//! Reads and compares every scan, several at a time across the cores; a scan that cannot be read or has
//! no face is a `ScanReport` with `failure`, and the others go on.
[[nodiscard]] Report compare_scans(const CompareRequest& request);
//! One scan file read and compared as `compare_scans` compares each (named `name`, `step` as in
//! `compare_scan`): a scan that cannot be read or has no face is a report with its `failure`, never an error.
[[nodiscard]] ScanReport compare_file(const std::filesystem::path& path, std::string_view name,
                                      const CompareOptions& options,
                                      const std::function<void(std::string_view)>& step = {});
//! The names `compare_scans` gives its inputs: their file names, a repeated one made unique (" (2)", ...);
//! the heat-map files are named after them.
[[nodiscard]] std::vector<std::string> scan_names(std::span<const std::filesystem::path> inputs);

//! The report's documents (`report.md`, `report.json`, `report.csv`, `rd.svg`, `report.html`) and the
//! heat-map GLBs, as files under `folder`, to be written as one set (`write_files_atomic`).
[[nodiscard]] std::vector<OutputFile> report_files(const Report& report, const std::filesystem::path& folder);
//! `report_files` written as one set (`write_files_atomic`), the folders they need made first and removed
//! again (when still empty) if the files cannot be written: every file or none. Returns how many were
//! written. Errors: `Io`.
[[nodiscard]] Result<std::size_t> write_report(const Report& report, const std::filesystem::path& folder);

[[nodiscard]] std::string report_markdown(const Report& report);
[[nodiscard]] std::string report_csv(const Report& report);
[[nodiscard]] std::string report_json(const Report& report);
//! Bytes (log axis) against the mean scan → result distance in the face mask, one series per method.
[[nodiscard]] std::string rd_svg(const Report& report);
//! Everything on one self-contained page (the plot and pictures inline).
[[nodiscard]] std::string report_html(const Report& report);

} // namespace pdeface::pipeline
