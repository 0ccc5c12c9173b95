#include "pdeface/core/file.hpp"

#include <fmt/format.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <system_error>
#include <utility>
#include <vector>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace pdeface {
namespace {

Error io_error(const std::filesystem::path& path, std::string_view what, int err) {
  return make_error(ErrorCode::Io, fmt::format("{}: {}", what, std::strerror(err)), source_name(path));
}

} // namespace

Result<std::string> read_file(const std::filesystem::path& path, std::uint64_t max_bytes) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    return make_error(ErrorCode::Io, "is a directory, not a file", source_name(path));
  std::ifstream in(path, std::ios::binary);
  if (!in) return io_error(path, "cannot open", errno);
  auto too_large = [&](std::string_view size) {
    return make_error(ErrorCode::CountTooLarge,
                      fmt::format("{}: more than the {} bytes a file may have", size, max_bytes),
                      source_name(path));
  };
  std::string bytes;
  const std::uintmax_t regular_size =
      std::filesystem::is_regular_file(path, ec) ? std::filesystem::file_size(path, ec) : 0;
  if (!ec && regular_size > max_bytes) return too_large(fmt::format("{} bytes", regular_size));
  if (!ec && regular_size > 0) {
    bytes.resize(static_cast<std::size_t>(regular_size));
    in.read(bytes.data(), static_cast<std::streamsize>(regular_size));
    bytes.resize(static_cast<std::size_t>(in.gcount()));
  }
  // A pipe, a device, or a file that grew: read on in chunks, never past the limit.
  constexpr std::size_t kChunk = std::size_t{1} << 20;
  // peek() first: after a regular file's last byte the stream is not yet at its end, and growing the
  // string by a chunk to find that out costs a megabyte of zeroes and its page faults (~1 ms) per read.
  while (in && in.peek() != std::ifstream::traits_type::eof()) {
    const std::size_t done = bytes.size();
    if (done > max_bytes) return too_large("the input goes on");
    bytes.resize(done + kChunk);
    in.read(bytes.data() + done, static_cast<std::streamsize>(kChunk));
    bytes.resize(done + static_cast<std::size_t>(in.gcount()));
  }
  if (bytes.size() > max_bytes) return too_large("the input goes on");
  if (in.bad()) return io_error(path, "cannot read", errno);
  return bytes;
}

namespace {

// Every byte of `bytes` written to `fd`; false with errno set when the system refuses.
bool write_all(int fd, std::string_view bytes) {
  for (std::size_t done = 0; done < bytes.size();) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    done += static_cast<std::size_t>(n);
  }
  return true;
}

// A new temporary file beside `path`, to be renamed over it: its name and descriptor.
Result<std::pair<std::string, int>> make_temporary(const std::filesystem::path& path) {
  const std::filesystem::path dir = path.has_parent_path() ? path.parent_path() : ".";
  std::string tmp = (dir / ("." + path.filename().string() + ".tmp-XXXXXX")).string();
  const int fd = ::mkstemp(tmp.data());
  if (fd < 0) return io_error(path, "cannot create a temporary file beside it", errno);
  return std::pair{std::move(tmp), fd};
}

// Closes a temporary file with the usual permissions of a new file (mkstemp creates 0600); on failure
// removes it and says why.
Result<void> close_temporary(const std::filesystem::path& path, const std::string& tmp, int fd) {
  ::fchmod(fd, 0644);
  if (::close(fd) == 0) return {};
  const int err = errno;
  ::unlink(tmp.c_str());
  return io_error(path, "cannot write", err);
}

// The bytes written to a temporary file beside `path`, closed: its name, for the rename.
Result<std::string> write_temporary(const std::filesystem::path& path, std::string_view bytes) {
  Result<std::pair<std::string, int>> made = make_temporary(path);
  if (!made) return std::move(made).error();
  auto& [tmp, fd] = *made;
  if (!write_all(fd, bytes)) {
    const int err = errno;
    ::close(fd);
    ::unlink(tmp.c_str());
    return io_error(path, "cannot write", err);
  }
  if (Result<void> closed = close_temporary(path, tmp, fd); !closed) return std::move(closed).error();
  return std::move(tmp);
}

} // namespace

Result<void> write_file_atomic(const std::filesystem::path& path, std::string_view bytes) {
  Result<AtomicFile> file = AtomicFile::create(path); // the bytes as they are, not a copy
  if (!file) return std::move(file).error();
  if (Result<void> written = file->append(bytes); !written) return written;
  return file->commit();
}

AtomicFile::AtomicFile(std::filesystem::path path, std::string temporary, int descriptor)
    : path_(std::move(path)), temporary_(std::move(temporary)), descriptor_(descriptor) {}

AtomicFile::AtomicFile(AtomicFile&& other) noexcept
    : path_(std::move(other.path_)), temporary_(std::move(other.temporary_)),
      descriptor_(std::exchange(other.descriptor_, -1)) {}

AtomicFile& AtomicFile::operator=(AtomicFile&& other) noexcept {
  if (this != &other) {
    abandon();
    path_ = std::move(other.path_);
    temporary_ = std::move(other.temporary_);
    descriptor_ = std::exchange(other.descriptor_, -1);
  }
  return *this;
}

AtomicFile::~AtomicFile() { abandon(); }

void AtomicFile::abandon() noexcept {
  if (descriptor_ < 0) return;
  ::close(descriptor_);
  ::unlink(temporary_.c_str());
  descriptor_ = -1;
}

Result<AtomicFile> AtomicFile::create(const std::filesystem::path& path) {
  Result<std::pair<std::string, int>> made = make_temporary(path);
  if (!made) return std::move(made).error();
  return AtomicFile(path, std::move(made->first), made->second);
}

Result<void> AtomicFile::append(std::string_view bytes) {
  if (descriptor_ < 0) throw std::logic_error("AtomicFile: append after commit or a failure");
  if (write_all(descriptor_, bytes)) return {};
  const int err = errno;
  abandon();
  return io_error(path_, "cannot write", err);
}

Result<void> AtomicFile::write_at(std::uint64_t offset, std::string_view bytes) {
  if (descriptor_ < 0) throw std::logic_error("AtomicFile: write after commit or a failure");
  for (std::size_t done = 0; done < bytes.size();) {
    const ssize_t n =
        ::pwrite(descriptor_, bytes.data() + done, bytes.size() - done, static_cast<off_t>(offset + done));
    if (n < 0) {
      if (errno == EINTR) continue;
      const int err = errno;
      abandon();
      return io_error(path_, "cannot write", err);
    }
    done += static_cast<std::size_t>(n);
  }
  return {};
}

Result<void> AtomicFile::commit() {
  if (descriptor_ < 0) throw std::logic_error("AtomicFile: commit twice or after a failure");
  const int fd = std::exchange(descriptor_, -1);
  if (Result<void> closed = close_temporary(path_, temporary_, fd); !closed) return closed;
  if (std::rename(temporary_.c_str(), path_.c_str()) != 0) {
    const int err = errno;
    ::unlink(temporary_.c_str());
    return io_error(path_, "cannot write", err);
  }
  return {};
}

Result<void> write_files_atomic(std::span<const OutputFile> files) {
  // Every file's bytes first; only when all are written does any file appear, by renames (which do not
  // fail for want of space or permission in a folder where a temporary file was just made).
  std::vector<std::string> temporaries;
  for (const OutputFile& f : files) {
    Result<std::string> tmp = write_temporary(f.path, f.bytes);
    if (!tmp) {
      for (const std::string& t : temporaries)
        ::unlink(t.c_str());
      return tmp.error();
    }
    temporaries.push_back(*std::move(tmp));
  }
  for (std::size_t i = 0; i < files.size(); ++i)
    if (std::rename(temporaries[i].c_str(), files[i].path.c_str()) != 0) {
      const int err = errno;
      for (std::size_t j = i; j < files.size(); ++j)
        ::unlink(temporaries[j].c_str());
      return io_error(files[i].path, "cannot write", err);
    }
  return {};
}

} // namespace pdeface
