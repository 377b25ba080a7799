// The pipe under the grader's wire format (wb_rpc.h): compiled into both the trusted test
// process and the worker.
#include "wb_rpc.h"

#include <unistd.h>
#include <cerrno>

namespace wbrpc {

void Channel::send(Out& o) {
  const std::uint32_t n = std::uint32_t(o.buf.size() - 4);
  if (o.buf.size() - 4 > kMaxMessage) throw ProtocolError("a message larger than the limit");
  std::memcpy(o.buf.data(), &n, 4);
  const char* p = o.buf.data();
  std::size_t left = o.buf.size();
  while (left > 0) {
    const ssize_t w = ::write(out_, p, left);
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0) throw ProtocolError("the other side closed the pipe");
    p += w, left -= std::size_t(w);
  }
}

static void read_all(int fd, char* p, std::size_t n) {
  while (n > 0) {
    const ssize_t r = ::read(fd, p, n);
    if (r < 0 && errno == EINTR) continue;
    if (r <= 0) throw ProtocolError("the other side closed the pipe");
    p += r, n -= std::size_t(r);
  }
}

In Channel::receive() {
  std::uint32_t n = 0;
  read_all(in_, reinterpret_cast<char*>(&n), 4);
  if (n > kMaxMessage) throw ProtocolError("a message larger than the limit");
  In in;
  in.buf.resize(n);
  read_all(in_, in.buf.data(), n);
  return in;
}

}  // namespace wbrpc
