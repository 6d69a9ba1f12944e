#include "hal/pgm_reader.hpp"

#include <fcntl.h>
#include <unistd.h>

namespace petra::hal {

namespace {

class Fd {
 public:
  explicit Fd(int fd) : fd_(fd) {}
  ~Fd() {
    if (fd_ >= 0) ::close(fd_);
  }
  Fd(const Fd&) = delete;
  Fd& operator=(const Fd&) = delete;
  int get() const { return fd_; }

 private:
  int fd_;
};

bool is_space(char c) {
  return c == ' ' || c == '\n' || c == '\r' || c == '\t';
}

// Reads the next header integer from text[pos...], skipping blanks and # comments.
bool next_int(const char* text, std::size_t n, std::size_t& pos, int& value) {
  for (;;) {
    while (pos < n && is_space(text[pos])) ++pos;
    if (pos < n && text[pos] == '#') {
      while (pos < n && text[pos] != '\n') ++pos;
      continue;
    }
    break;
  }
  if (pos >= n || text[pos] < '0' || text[pos] > '9') return false;
  long v = 0;
  while (pos < n && text[pos] >= '0' && text[pos] <= '9') {
    v = v * 10 + (text[pos] - '0');
    if (v > 1000000) return false;
    ++pos;
  }
  value = static_cast<int>(v);
  return true;
}

}  // namespace

Result<PgmReader::Header> PgmReader::parse_header(const char* path, int fd) {
  const ssize_t n = ::pread(fd, chunk_.data(), chunk_.size(), 0);
  if (n < 2) return Error::make(Errc::parse_error, "%s: too short for a PGM", path);
  const auto len = static_cast<std::size_t>(n);
  if (chunk_[0] != 'P' || chunk_[1] != '5')
    return Error::make(Errc::parse_error, "%s: not a binary PGM (magic must be P5)", path);
  Header h;
  std::size_t pos = 2;
  if (!next_int(chunk_.data(), len, pos, h.size.width) || h.size.width <= 0)
    return Error::make(Errc::parse_error, "%s: PGM width missing or not positive", path);
  if (!next_int(chunk_.data(), len, pos, h.size.height) || h.size.height <= 0)
    return Error::make(Errc::parse_error, "%s: PGM height missing or not positive", path);
  if (!next_int(chunk_.data(), len, pos, h.maxval) || h.maxval <= 0 || h.maxval > 255)
    return Error::make(Errc::parse_error, "%s: PGM maxval must be 1..255 (8-bit)", path);
  if (pos >= len || !is_space(chunk_[pos]))
    return Error::make(Errc::parse_error, "%s: PGM header not followed by one blank", path);
  h.data_offset = pos + 1;
  return h;
}

Result<PgmSize> PgmReader::read_size(const char* path) {
  Fd fd(::open(path, O_RDONLY | O_CLOEXEC));
  if (fd.get() < 0) return Error::make(Errc::io_error, "%s: cannot open", path);
  auto h = parse_header(path, fd.get());
  if (!h) return h.error();
  return h->size;
}

Status PgmReader::read(const char* path, Gray8View dst) {
  Fd fd(::open(path, O_RDONLY | O_CLOEXEC));
  if (fd.get() < 0) return Error::make(Errc::io_error, "%s: cannot open", path);
  auto h = parse_header(path, fd.get());
  if (!h) return h.error();
  if (h->size.width != dst.width() || h->size.height != dst.height())
    return Error::make(Errc::invalid_argument, "%s: %dx%d px, camera expects %dx%d", path,
                       h->size.width, h->size.height, dst.width(), dst.height());
  const std::size_t row_bytes = static_cast<std::size_t>(dst.width());
  auto offset = static_cast<off_t>(h->data_offset);
  for (int y = 0; y < dst.height(); ++y) {
    std::size_t got = 0;
    while (got < row_bytes) {  // bounded: each pass reads >= 1 byte or fails
      const ssize_t n = ::pread(fd.get(), dst.row(y) + got, row_bytes - got, offset);
      if (n <= 0) return Error::make(Errc::parse_error, "%s: truncated at row %d", path, y);
      got += static_cast<std::size_t>(n);
      offset += n;
    }
  }
  return {};
}

}  // namespace petra::hal
