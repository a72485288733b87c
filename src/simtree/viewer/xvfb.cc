#include "simtree/viewer/xvfb.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <cstring>
#include <vector>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "simtree/core/error.h"

extern char** environ;

namespace simtree::viewer {

bool HasDisplay() {
  const char* display = std::getenv("DISPLAY");
  if (display == nullptr || display[0] == '\0') return false;
  // Local displays ":N" or ":N.S": the server listens on /tmp/.X11-unix/XN.
  if (display[0] != ':') return true;  // a remote display: trust it
  const std::string number = std::string(display + 1).substr(0, std::strcspn(display + 1, "."));
  const std::string path = "/tmp/.X11-unix/X" + number;
  const int fd = socket(AF_UNIX, SOCK_STREAM, 0);
  if (fd < 0) return false;
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  std::strncpy(address.sun_path, path.c_str(), sizeof(address.sun_path) - 1);
  const bool ok = connect(fd, reinterpret_cast<sockaddr*>(&address), sizeof(address)) == 0;
  close(fd);
  return ok;
}

ScopedXvfb::ScopedXvfb(int width, int height, double timeout_s) {
  int fds[2];
  if (pipe(fds) != 0) throw Error("Xvfb: cannot create a pipe");
  const std::string fd_text = std::to_string(fds[1]);
  const std::string screen = fmt::format("{}x{}x24", width, height);
  std::vector<std::string> args = {"Xvfb", "-displayfd", fd_text, "-screen", "0",
                                   screen, "-nolisten",  "tcp",   "-noreset"};
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addclose(&actions, fds[0]);
  // Xvfb's chatter (font and keymap warnings) is not ours to show.
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, "/dev/null", O_WRONLY, 0);
  const int spawned = posix_spawnp(&pid_, "Xvfb", &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  close(fds[1]);
  if (spawned != 0) {
    close(fds[0]);
    throw Error("Xvfb is not installed (apt-get install xvfb): cannot make a virtual display");
  }
  // Xvfb writes its display number and a newline once it accepts connections.
  std::string number;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (number.find('\n') == std::string::npos) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
                          deadline - std::chrono::steady_clock::now())
                          .count();
    pollfd p{fds[0], POLLIN, 0};
    if (left <= 0 || poll(&p, 1, static_cast<int>(left)) <= 0) break;
    char buffer[32];
    const ssize_t n = read(fds[0], buffer, sizeof(buffer));
    if (n <= 0) break;
    number.append(buffer, static_cast<size_t>(n));
  }
  close(fds[0]);
  if (number.find('\n') == std::string::npos) {
    kill(pid_, SIGTERM);
    waitpid(pid_, nullptr, 0);
    throw Error(fmt::format("Xvfb did not start within {} s", timeout_s));
  }
  display_ = ":" + number.substr(0, number.find('\n'));
  if (const char* old = std::getenv("DISPLAY")) previous_display_ = old;
  setenv("DISPLAY", display_.c_str(), 1);
  spdlog::info("started Xvfb on display {} ({}): software OpenGL with no screen", display_, screen);
}

ScopedXvfb::~ScopedXvfb() {
  if (pid_ > 0) {
    kill(pid_, SIGTERM);
    waitpid(pid_, nullptr, 0);
  }
  if (previous_display_) {
    setenv("DISPLAY", previous_display_->c_str(), 1);
  } else {
    unsetenv("DISPLAY");
  }
}

}  // namespace simtree::viewer
