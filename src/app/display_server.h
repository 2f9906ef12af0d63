// `lantern render --display-server HOST:PORT`: the image, as it refines,
// streamed to a display server that speaks tev's IPC protocol (tev shows
// it; pbrt-v4's --display-server sends the same packets).
//
// A packet is its length (uint32, the length field included), a type byte
// and the payload, integers little-endian, strings terminated by a zero
// byte. Lantern sends CreateImage (type 4: grab focus, name, width, height,
// channel count, channel names) once, then UpdateImageV3 (type 6: grab
// focus, name, channel count, channel names, x, y, width, height, an int64
// offset and an int64 stride per channel, then the floats) for bands of
// rows; its interleaved RGB goes as offsets 0, 1, 2 and stride 3, without
// a copy into planes.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "app/session_watcher.h"
#include "lantern/render.h"

namespace lantern {

class DisplayServer {
 public:
  // Connects (throws std::runtime_error, naming the address and why, when
  // it cannot) and creates an image `name` of the session's size.
  DisplayServer(const std::string& address, const std::string& name, int width, int height);
  ~DisplayServer();
  DisplayServer(const DisplayServer&) = delete;
  DisplayServer& operator=(const DisplayServer&) = delete;

  // Sends the session's image every `interval` seconds and after each pass
  // (call pass_done() from RenderHooks::pass_done), on a thread of its own
  // (app/session_watcher.h), until stop().
  void watch(const RenderSession& session, double interval = 1.0);
  void pass_done(uint32_t spp);
  // Stops watching, then sends `final` (the finished render's image).
  void stop(const Image& final);
  bool connected() const { return socket_ >= 0; }

 private:
  void send_image(const Image& image);
  void send(const std::string& packet);

  int socket_ = -1;
  std::string name_;
  int width_ = 0, height_ = 0;
  std::unique_ptr<SessionWatcher> watcher_;
};

}  // namespace lantern
