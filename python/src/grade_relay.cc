// crankcheck-grade-relay SOCKET: the program `crankcheck.grade` lets `crankcheck grade --batch` start (grade_bridge.h).
// It connects to the grading Python process's Unix socket, passes everything it reads on stdin there, then copies the
// answer to stdout. Not meant to be run by hand.

#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

namespace {

bool writeAll(int fd, const char* data, size_t size, bool socket) {
  while (size > 0) {
    const ssize_t n = socket ? ::send(fd, data, size, MSG_NOSIGNAL) : ::write(fd, data, size);
    if (n < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    data += n;
    size -= static_cast<size_t>(n);
  }
  return true;
}

// Copies `from` to `to` until end of file. False on an error.
bool pump(int from, int to, bool to_socket) {
  char buffer[65536];
  for (;;) {
    const ssize_t got = ::read(from, buffer, sizeof buffer);
    if (got == 0) return true;
    if (got < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    if (!writeAll(to, buffer, static_cast<size_t>(got), to_socket)) return false;
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "crankcheck-grade-relay: usage: crankcheck-grade-relay SOCKET (started by crankcheck.grade)\n");
    return 2;
  }
  const int fd = ::socket(AF_UNIX, SOCK_STREAM, 0);
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  if (std::strlen(argv[1]) >= sizeof address.sun_path) {
    std::fprintf(stderr, "crankcheck-grade-relay: %s: socket path too long\n", argv[1]);
    return 3;
  }
  std::strcpy(address.sun_path, argv[1]);
  if (fd < 0 || ::connect(fd, reinterpret_cast<const sockaddr*>(&address), sizeof address) != 0) {
    std::fprintf(stderr, "crankcheck-grade-relay: %s: cannot connect: %s\n", argv[1], std::strerror(errno));
    return 3;
  }
  // The requests in (the grading process answers once it has them all), then the answers out.
  const bool sent = pump(STDIN_FILENO, fd, true);
  ::shutdown(fd, SHUT_WR);
  if (!pump(fd, STDOUT_FILENO, false)) {
    std::fprintf(stderr, "crankcheck-grade-relay: cannot copy the answers: %s\n", std::strerror(errno));
    return 3;
  }
  ::close(fd);
  if (!sent) {
    std::fprintf(stderr, "crankcheck-grade-relay: the grading process closed the connection before the last request\n");
    return 3;
  }
  return 0;
}
