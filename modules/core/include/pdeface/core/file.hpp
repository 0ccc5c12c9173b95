#pragma once
//! \file
//! Whole-file reads and atomic writes: readers parse from memory, writers never leave half a file.

#include "pdeface/core/result.hpp"

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>

namespace pdeface {

//! The most bytes `read_file` reads: 512 MiB, far above any face scan (a million-vertex ASCII PLY has ~60
//! MB), and a bound on what a device (`/dev/zero`), a pipe or a huge file can make a command allocate.
inline constexpr std::uint64_t kMaxFileBytes = std::uint64_t{1} << 29;

//! The bytes of a file, a pipe or a device, at most `max_bytes` of them. Errors: `Io` (cannot open or read;
//! a directory), `CountTooLarge` (more than `max_bytes`: nothing more is read).
[[nodiscard]] Result<std::string> read_file(const std::filesystem::path& path,
                                            std::uint64_t max_bytes = kMaxFileBytes);

//! Writes `bytes` to a temporary file beside `path`, then renames it over `path`: readers of `path` see
//! either the old file or the complete new one, and a failure leaves nothing behind.
[[nodiscard]] Result<void> write_file_atomic(const std::filesystem::path& path, std::string_view bytes);

//! One file of a command's output.
struct OutputFile {
  std::filesystem::path path;
  std::string bytes;
};

//! Writes several files as a set: every one to a temporary file beside it first, and only when all are
//! written, each renamed over its path. A failure while writing (a missing folder, a full disk) leaves
//! none of them behind and no temporary file either.
[[nodiscard]] Result<void> write_files_atomic(std::span<const OutputFile> files);

//! A file written in pieces and published whole, for output too large to hold in memory first: the pieces
//! go to a temporary file beside the path, and `commit` renames it over the path. Until then readers of
//! the path see the old file (or none); destroyed uncommitted (an error, an exception), it removes the
//! temporary file and leaves nothing behind. `write_file_atomic` is this with one piece.
class AtomicFile {
public:
  //! Errors: `Io` when no temporary file can be made beside `path` (a missing folder, no permission).
  [[nodiscard]] static Result<AtomicFile> create(const std::filesystem::path& path);

  AtomicFile(AtomicFile&& other) noexcept;
  AtomicFile& operator=(AtomicFile&& other) noexcept;
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;
  ~AtomicFile();

  //! Appends `bytes`. Errors: `Io` (a full disk); the file is then abandoned.
  [[nodiscard]] Result<void> append(std::string_view bytes);
  //! Writes `bytes` at `offset` (the file grows as needed; a gap reads as zeros until written), for output
  //! made out of order; `append` continues after what it appended last. Errors: as `append`.
  [[nodiscard]] Result<void> write_at(std::uint64_t offset, std::string_view bytes);
  //! Closes the temporary file and renames it over the path. Errors: `Io`; nothing is left behind.
  //! \throw std::logic_error when called twice or after a failed append
  [[nodiscard]] Result<void> commit();

private:
  AtomicFile(std::filesystem::path path, std::string temporary, int descriptor);
  void abandon() noexcept;

  std::filesystem::path path_;
  std::string temporary_;
  int descriptor_ = -1;
};

//! The file name to put in error messages: the path as the user gave it.
[[nodiscard]] inline std::string source_name(const std::filesystem::path& path) { return path.string(); }

} // namespace pdeface
