#include "io/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>
#include <vector>

#include <fmt/format.h>

namespace rtsph::io {
namespace {

namespace fs = std::filesystem;

std::string os_error(int err) { return std::strerror(err); }

/// Returns 0 or the errno of the failed write; loops because write() may be partial.
int write_all(int fd, const char* data, std::size_t n) {
  while (n > 0) {
    ssize_t w = ::write(fd, data, n);
    if (w < 0) {
      if (errno == EINTR) continue;
      return errno;
    }
    data += w;
    n -= static_cast<std::size_t>(w);
  }
  return 0;
}

/// A stream buffer on a raw descriptor, because fsync needs the descriptor and std::ofstream
/// hides it. Remembers the first errno so the caller can report ENOSPC rather than "failed".
class FdBuf : public std::streambuf {
 public:
  explicit FdBuf(int fd) : fd_(fd), buf_(1 << 16) { setp(buf_.data(), buf_.data() + buf_.size()); }
  int error() const { return err_; }

 protected:
  int_type overflow(int_type c) override {
    if (!drain()) return traits_type::eof();
    if (!traits_type::eq_int_type(c, traits_type::eof())) {
      *pptr() = traits_type::to_char_type(c);
      pbump(1);
    }
    return traits_type::not_eof(c);
  }
  std::streamsize xsputn(const char* s, std::streamsize n) override {
    if (n <= 0) return 0;  // an empty write may come with a null pointer; memcpy must not see it
    if (n < epptr() - pptr()) {
      std::memcpy(pptr(), s, static_cast<std::size_t>(n));
      pbump(static_cast<int>(n));
      return n;
    }
    if (!drain()) return 0;
    if (err_ = write_all(fd_, s, static_cast<std::size_t>(n)); err_) return 0;
    return n;
  }
  int sync() override { return drain() ? 0 : -1; }

 private:
  bool drain() {
    if (err_) return false;
    err_ = write_all(fd_, pbase(), static_cast<std::size_t>(pptr() - pbase()));
    setp(buf_.data(), buf_.data() + buf_.size());
    return err_ == 0;
  }
  int fd_;
  int err_ = 0;
  std::vector<char> buf_;
};

/// Owns the temporary file until it has been renamed into place.
class TempFile {
 public:
  explicit TempFile(fs::path p) : path_(std::move(p)) {}
  TempFile(const TempFile&) = delete;
  TempFile& operator=(const TempFile&) = delete;
  ~TempFile() {
    if (fd_ >= 0) ::close(fd_);
    if (!committed_) ::unlink(path_.c_str());
  }
  int open() {
    fd_ = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
    return fd_ < 0 ? errno : 0;
  }
  int close() {
    int r = ::close(fd_);
    fd_ = -1;
    return r < 0 ? errno : 0;
  }
  int fd() const { return fd_; }
  const fs::path& path() const { return path_; }
  void committed() { committed_ = true; }

 private:
  fs::path path_;
  int fd_ = -1;
  bool committed_ = false;
};

[[noreturn]] void fail(const char* what, const fs::path& path, int err) {
  throw IoError(fmt::format("cannot {} '{}': {}", what, path.string(), os_error(err)));
}

/// Makes the rename itself durable. Some filesystems cannot fsync a directory (EINVAL); the
/// file content is already safe there, so that is not an error.
void sync_directory(const fs::path& dir, const fs::path& file) {
  int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) fail("sync directory of", file, errno);
  int err = ::fsync(fd) < 0 ? errno : 0;
  ::close(fd);
  if (err && err != EINVAL) fail("sync directory of", file, err);
}

}  // namespace

void write_file_atomic(const fs::path& path, const std::function<void(std::ostream&)>& body) {
  if (!path.has_filename()) throw IoError(fmt::format("cannot write '{}': not a file name", path.string()));
  const fs::path dir = path.has_parent_path() ? path.parent_path() : fs::path(".");
  TempFile tmp(dir / fmt::format(".{}.tmp.{}", path.filename().string(), ::getpid()));
  if (int err = tmp.open()) fail("write", path, err);
  {
    FdBuf buf(tmp.fd());
    std::ostream os(&buf);
    body(os);
    os.flush();
    if (buf.error()) fail("write", path, buf.error());
    if (!os) throw IoError(fmt::format("cannot write '{}': stream error", path.string()));
  }
  if (::fsync(tmp.fd()) < 0) fail("write", path, errno);
  if (int err = tmp.close()) fail("write", path, err);
  if (::rename(tmp.path().c_str(), path.c_str()) < 0) fail("replace", path, errno);
  tmp.committed();
  sync_directory(dir, path);
}

void write_file_atomic(const fs::path& path, std::string_view bytes) {
  write_file_atomic(path, [&](std::ostream& os) { os.write(bytes.data(), static_cast<std::streamsize>(bytes.size())); });
}

void write_file_atomic_via_path(const fs::path& path, const std::function<void(const fs::path&)>& body) {
  if (!path.has_filename()) throw IoError(fmt::format("cannot write '{}': not a file name", path.string()));
  const fs::path dir = path.has_parent_path() ? path.parent_path() : fs::path(".");
  TempFile tmp(dir / fmt::format(".{}.tmp.{}", path.filename().string(), ::getpid()));
  // Created (and closed) first: proves the directory is writable, and the destructor removes
  // whatever `body` leaves there if it throws.
  if (int err = tmp.open()) fail("write", path, err);
  if (int err = tmp.close()) fail("write", path, err);
  body(tmp.path());
  // The library closed its own descriptor; reopen to fsync what it wrote.
  const int fd = ::open(tmp.path().c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) fail("write", path, errno);
  const int err = ::fsync(fd) < 0 ? errno : 0;
  ::close(fd);
  if (err) fail("write", path, err);
  if (::rename(tmp.path().c_str(), path.c_str()) < 0) fail("replace", path, errno);
  tmp.committed();
  sync_directory(dir, path);
}

void ensure_directory(const fs::path& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) {
    throw IoError(fmt::format("cannot create directory '{}': {}", dir.string(), ec.message()));
  }
  if (!fs::is_directory(dir, ec)) {
    throw IoError(fmt::format("cannot create directory '{}': exists and is not a directory", dir.string()));
  }
}

void check_file_target(const fs::path& path) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) throw IoError(fmt::format("cannot write '{}': it is a directory", path.string()));
  const fs::path dir = fs::absolute(path, ec).parent_path();
  if (ec || !fs::is_directory(dir, ec))
    throw IoError(fmt::format("cannot write '{}': no directory '{}'", path.string(), dir.string()));
}

}  // namespace rtsph::io
