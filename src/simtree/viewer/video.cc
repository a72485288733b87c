#include "simtree/viewer/video.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <vector>

#include <fmt/format.h>

#include "simtree/core/atomic_file.h"
#include "simtree/core/error.h"
#include "simtree/core/option_checks.h"

extern char** environ;

namespace simtree::viewer {

void VideoOptions::Validate() const {
  CheckOption(fps > 0.0 && std::isfinite(fps), "video options", "fps",
              fmt::format("expected a frame rate > 0, got {}", fps));
  CheckOption(crf >= 0 && crf <= 51, "video options", "crf",
              fmt::format("expected 0 to 51, got {}", crf));
  CheckOption(!pattern.empty(), "video options", "pattern",
              "expected a frame file name pattern such as %06d.png");
}

void EncodeVideo(const std::filesystem::path& frames_dir, const std::filesystem::path& output,
                 const VideoOptions& options) {
  options.Validate();
  if (output.has_parent_path()) std::filesystem::create_directories(output.parent_path());
  // Written beside the target under a name ffmpeg still recognises by its extension.
  const std::filesystem::path partial =
      output.parent_path() /
      fmt::format(".{}.partial{}", output.stem().string(), output.extension().string());
  const std::filesystem::path log =
      output.parent_path() / fmt::format(".{}.log", output.filename().string());
  std::vector<std::string> args = {
      "ffmpeg", "-nostdin", "-y", "-loglevel", "error", "-framerate",
      fmt::format("{}", options.fps), "-i", (frames_dir / options.pattern).string(),
      // x264 with yuv420p needs even sizes.
      "-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2", "-c:v", "libx264", "-preset", "medium", "-crf",
      std::to_string(options.crf), "-pix_fmt", "yuv420p", "-movflags", "+faststart",
      partial.string()};
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, log.c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0644);
  pid_t pid = -1;
  const int spawned = posix_spawnp(&pid, "ffmpeg", &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) {
    std::filesystem::remove(log);
    throw Error("video: ffmpeg is not installed (apt-get install ffmpeg)");
  }
  int status = 0;
  waitpid(pid, &status, 0);
  std::string messages;
  if (std::filesystem::exists(log)) messages = ReadFile(log);
  std::filesystem::remove(log);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || !std::filesystem::exists(partial)) {
    std::filesystem::remove(partial);
    if (messages.size() > 600) messages = "..." + messages.substr(messages.size() - 600);
    throw Error(fmt::format("video: ffmpeg failed writing {}: {}", output.string(), messages));
  }
  std::filesystem::rename(partial, output);
}

}  // namespace simtree::viewer
