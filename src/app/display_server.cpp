#include "app/display_server.h"

#include "app/log.h"

#include <netdb.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <stdexcept>

namespace lantern {

namespace {

// A packet under construction: the length field first, filled in at the end.
class Packet {
 public:
  explicit Packet(uint8_t type) {
    put(uint32_t(0));
    put(type);
  }
  template <class T>
  Packet& put(T v) {
    const char* p = reinterpret_cast<const char*>(&v);  // little-endian on every machine Lantern builds for
    bytes_.append(p, sizeof v);
    return *this;
  }
  Packet& put(const std::string& s) {
    bytes_.append(s);
    bytes_.push_back('\0');
    return *this;
  }
  Packet& put(const float* data, size_t n) {
    bytes_.append(reinterpret_cast<const char*>(data), n * sizeof(float));
    return *this;
  }
  std::string done() {
    const uint32_t n = uint32_t(bytes_.size());
    std::memcpy(bytes_.data(), &n, sizeof n);
    return std::move(bytes_);
  }

 private:
  std::string bytes_;
};

constexpr uint8_t kCreateImage = 4, kUpdateImageV3 = 6;
const char* const kChannels[3] = {"R", "G", "B"};

int connect_to(const std::string& address) {
  const size_t colon = address.rfind(':');
  if (colon == std::string::npos || colon == 0 || colon + 1 == address.size())
    throw std::runtime_error("--display-server \"" + address + "\": expected HOST:PORT (tev listens on 127.0.0.1:14158)");
  const std::string host = address.substr(0, colon), port = address.substr(colon + 1);
  addrinfo hints{};
  hints.ai_family = AF_UNSPEC;
  hints.ai_socktype = SOCK_STREAM;
  addrinfo* found = nullptr;
  if (const int err = ::getaddrinfo(host.c_str(), port.c_str(), &hints, &found); err != 0)
    throw std::runtime_error("display server " + address + ": " + ::gai_strerror(err));
  int fd = -1;
  std::string why = "no address";
  for (addrinfo* a = found; a && fd < 0; a = a->ai_next) {
    fd = ::socket(a->ai_family, a->ai_socktype, a->ai_protocol);
    if (fd >= 0 && ::connect(fd, a->ai_addr, a->ai_addrlen) != 0) {
      why = std::strerror(errno);
      ::close(fd);
      fd = -1;
    }
  }
  ::freeaddrinfo(found);
  if (fd < 0) throw std::runtime_error("display server " + address + ": cannot connect (" + why + "; is tev running?)");
  return fd;
}

}  // namespace

DisplayServer::DisplayServer(const std::string& address, const std::string& name, int width, int height)
    : socket_(connect_to(address)), name_(name), width_(width), height_(height) {
  Packet p(kCreateImage);
  p.put(uint8_t(1)).put(name_).put(int32_t(width)).put(int32_t(height)).put(int32_t(3));
  for (const char* c : kChannels) p.put(std::string(c));
  send(p.done());
}

DisplayServer::~DisplayServer() {
  watcher_.reset();  // its thread sends
  if (socket_ >= 0) ::close(socket_);
}

void DisplayServer::send(const std::string& packet) {
  size_t sent = 0;
  while (socket_ >= 0 && sent < packet.size()) {
    const ssize_t n = ::send(socket_, packet.data() + sent, packet.size() - sent, MSG_NOSIGNAL);
    if (n <= 0) {
      // The viewer went away: the render goes on without it.
      logging::warning("warning: display server: %s; no more updates are sent",
                   n < 0 ? std::strerror(errno) : "connection closed");
      ::close(socket_);
      socket_ = -1;
      return;
    }
    sent += size_t(n);
  }
}

// Bands of rows of at most about 4 MB each.
void DisplayServer::send_image(const Image& image) {
  if (image.width != width_ || image.height != height_ || image.rgb.empty()) return;
  const int rows = std::max(1, int((size_t(1) << 20) / (size_t(width_) * 3)));
  for (int y0 = 0; y0 < height_ && socket_ >= 0; y0 += rows) {
    const int h = std::min(rows, height_ - y0);
    Packet p(kUpdateImageV3);
    p.put(uint8_t(0)).put(name_).put(int32_t(3));
    for (const char* c : kChannels) p.put(std::string(c));
    p.put(int32_t(0)).put(int32_t(y0)).put(int32_t(width_)).put(int32_t(h));
    for (int64_t c = 0; c < 3; ++c) p.put(c);
    for (int c = 0; c < 3; ++c) p.put(int64_t(3));
    // The last channel's last value ends the data: offset 2 + (n - 1) * 3 + 1 floats.
    p.put(image.at(0, y0), size_t(width_) * size_t(h) * 3);
    send(p.done());
  }
}

void DisplayServer::watch(const RenderSession& session, double interval) {
  watcher_ = std::make_unique<SessionWatcher>([this](const Image& image, uint32_t) { send_image(image); }, interval, 0.0);
  watcher_->watch(session);
}

void DisplayServer::pass_done(uint32_t spp) {
  if (watcher_) watcher_->pass_done(spp);
}

void DisplayServer::stop(const Image& final) {
  if (watcher_) watcher_->stop();
  send_image(final);
}

}  // namespace lantern
