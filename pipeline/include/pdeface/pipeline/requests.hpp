#pragma once
//! \file
//! The commands' steps as the library runs them, on a scan already read: aligned (landmarks detected or
//! from a file's bytes), sliced, reconstructed, measured; the documents they write made as values. The
//! command line only reads the files, fills these requests and writes what comes back.

#include "pdeface/align/pipeline.hpp"
#include "pdeface/core/mesh.hpp"
#include "pdeface/core/result.hpp"
#include "pdeface/metrics/fidelity.hpp"
#include "pdeface/pipeline/reconstruct.hpp"
#include "pdeface/pipeline/table.hpp"

#include <optional>
#include <string>
#include <vector>

namespace pdeface::pipeline {

struct ProfilesRequest {
  align::LandmarkSource landmarks;
  slice::ProfileOptions profiles;
  bool svg = false;   //!< also make the picture (`slice::profiles_svg`)
  std::string source; //!< the scan's name, for errors and the picture's title
};

struct ProfilesOutcome {
  align::Alignment alignment;
  slice::ProfileSet profiles;
  std::string json; //!< `slice::write_profiles_json`
  std::string svg;  //!< when asked
};

//! `pdeface profiles`: aligned, sliced, written as documents. Errors name `request.source` (or the
//! landmark file).
[[nodiscard]] Result<ProfilesOutcome> profiles_request(const Mesh& scan, const ProfilesRequest& request);

struct ReconstructRequest {
  align::LandmarkSource landmarks;
  ReconstructOptions options;
  bool profiles_json = false; //!< also make the curves' document
  bool preview = false;       //!< also make the picture (`reconstruction_preview_svg`)
  std::string source;         //!< the scan's name
  metrics::CheckLimits check; //!< what the reconstruction must meet (`self_check`)
  //! A reconstruction that fails its self-check is returned anyway (`ReconstructOutcome::check` says what
  //! failed) instead of as a `SelfCheck` error.
  bool force = false;
};

struct ReconstructOutcome {
  align::Alignment alignment;
  Reconstruction reconstruction;
  std::optional<metrics::Fidelity> fidelity; //!< how faithful it is (mm), or why it could not be measured:
  std::string fidelity_failure;
  metrics::SelfCheck check; //!< the reconstruction against the scan on its face mask (passed, unless `force`)
  double scan_units_per_mm = 1.0; //!< to state distances in the scan's own units
  std::string profiles_json;      //!< when asked
  std::string preview_svg;        //!< when asked
};

//! `pdeface reconstruct`: aligned, reconstructed (`reconstruct`), measured (`measure_fidelity`; a
//! measurement that fails is reported in the outcome, not as an error) and checked (`self_check` on the
//! face mask). Errors name `request.source`; `SelfCheck` when the reconstruction is off (unless `force`).
[[nodiscard]] Result<ReconstructOutcome> reconstruct_request(const Mesh& scan,
                                                             const ReconstructRequest& request);

//! `pdeface table` on one scan: landmarks detected, every ratio × scheme of `options` (`table_rows`).
//! Errors name `source`.
[[nodiscard]] Result<std::vector<TableRow>> table_request(const Mesh& scan, const TableOptions& options,
                                                          std::string_view source);

} // namespace pdeface::pipeline
