#pragma once
// What the commands share: exit codes, how notes and errors are printed, reading the inputs, writing the
// outputs as a set, and the options several commands take.

#include "pdeface/align/pipeline.hpp"
#include "pdeface/core/file.hpp"
#include "pdeface/core/names.hpp"
#include "pdeface/formats/formats.hpp"
#include "pdeface/pde/surface.hpp"
#include "pdeface/pipeline/encode.hpp"
#include "pdeface/pipeline/reconstruct.hpp"
#include "pdeface/slice/profiles.hpp"

#include <CLI/CLI.hpp>

#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace pdeface::cli {

namespace fs = std::filesystem;

inline constexpr int kDataError = 1;     // the input or output could not be read, converted or written
inline constexpr int kUsageError = 2;    // the command line itself is wrong
inline constexpr int kInternalError = 3; // a bug: an exception reached the command line

//! A command: adds its subcommand to `app`; when that is the one given, runs it and sets `status`.
using Command = void (*)(CLI::App& app, int& status);
void info_command(CLI::App& app, int& status);
void convert_command(CLI::App& app, int& status);
void sample_command(CLI::App& app, int& status);
void align_command(CLI::App& app, int& status);
void profiles_command(CLI::App& app, int& status);
void reconstruct_command(CLI::App& app, int& status);
void table_command(CLI::App& app, int& status);
void compare_command(CLI::App& app, int& status);
void encode_command(CLI::App& app, int& status);
void decode_command(CLI::App& app, int& status);

//! Prints the notes collected so far and forgets them, so that the next step's are printed once.
void print_notes(Notes& notes);
//! Prints the error as one line on stderr; the data-error exit status.
int fail(const Error& error);

//! A mesh read from a file, its notes printed.
[[nodiscard]] Result<formats::LoadedMesh> read_scan(const std::filesystem::path& in);

//! The bytes of the landmark file `file` (none when it is empty: detect them).
[[nodiscard]] Result<align::LandmarkSource> landmark_source(const std::filesystem::path& file);

//! A scan and the landmarks it is to be aligned by.
struct ScanAndLandmarks {
  formats::LoadedMesh scan;
  align::LandmarkSource landmarks; // none: detect them
};
//! The scan in `in` (its notes printed), and the bytes of the landmark file `landmarks` (none when it is
//! empty: detect them).
[[nodiscard]] Result<ScanAndLandmarks> read_scan_and_landmarks(const std::filesystem::path& in,
                                                               const std::filesystem::path& landmarks);
//! The outputs of a command, written as a set (none if any fails).
[[nodiscard]] Result<void> write_outputs(std::span<const OutputFile> files);

//! A choice among an enum's names (aliases too).
template <class E> CLI::IsMember one_of(std::span<const NamedValue<E>> names) {
  return CLI::IsMember(all_names(names));
}
//! The value a name the command line accepted (`one_of`) stands for.
template <class E> E named(std::span<const NamedValue<E>> names, const std::string& name) {
  return value_named(names, name).value();
}

void add_input(CLI::App* cmd, std::filesystem::path& in, const std::string& description);
//! The required -o,--output.
void add_output(CLI::App* cmd, std::filesystem::path& out, const std::string& description);
//! --landmarks: a landmark file to use instead of detecting them.
void add_landmarks(CLI::App* cmd, std::filesystem::path& landmarks);
//! --resolution V or UxV: the surface's grid (V along the face's height, U across), parsed here for every
//! command that takes it.
struct ResolutionArg {
  std::vector<std::size_t> values; // as given: {v} or {u, v}
  //! The grid asked for (u = 0: as many across as keep the cells square), or none: the default spacing.
  [[nodiscard]] std::optional<pipeline::Resolution> grid() const;
};
void add_resolution(CLI::App* cmd, ResolutionArg& resolution);
void add_write_options(CLI::App* cmd, formats::WriteOptions& write);

//! How a scan becomes curves: landmarks given or detected, and the slicing options.
struct CurveArgs {
  std::filesystem::path landmarks; // given landmarks instead of detection
  std::string parameter = "arc";
  std::string sampling = "local";
  std::string fit = "cosine";
  std::optional<std::size_t> points;
  slice::ProfileOptions options;
  CLI::Option* ratio_option = nullptr; // set by add_to

  void add_to(CLI::App* cmd, bool with_landmarks = true);
  [[nodiscard]] slice::ProfileOptions profile_options() const;
  //! The command line named the curves' points (`--ratio` or `--points`).
  [[nodiscard]] bool ratio_given() const { return points || (ratio_option && ratio_option->count() > 0); }
};

//! How curves become a surface.
struct SurfaceArgs {
  std::string scheme = "spline";
  std::string spacing = "physical";
  pde::Options options;

  void add_to(CLI::App* cmd, bool with_scheme = true);
  [[nodiscard]] pde::Options pde_options() const;
};

//! `--force`: write a result that fails its self-check anyway, with a warning.
void add_force(CLI::App* cmd, bool& force);
//! The self-check of what was written: a warning on stderr when it failed (written with `--force`), else
//! one line of its figures.
void print_check(const metrics::SelfCheck& check);

//! What slicing filled and what the scan lacks, as notes on stderr.
void print_holes_and_gaps(const slice::ProfileSet& set);

//! `pdeface encode` (and `convert scan face.pdef`): reads the scan, runs `pipeline::encode_request`, writes
//! the document atomically and prints what it holds; the exit status. `out` must end in .pdef.
int encode_scan(const std::filesystem::path& in, const std::filesystem::path& out,
                const pipeline::EncodeRequest& request);

} // namespace pdeface::cli
