#include "video_encoder.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <vector>

#include <fmt/format.h>

#include "luxel/error.h"
#include "io/atomic_file.h"
#include "output_paths.h"
#include "progress_bar.h"

extern char** environ;

namespace luxel::cli {
namespace {

namespace fs = std::filesystem;

// The last `lines` lines of a file, for an error message.
std::string tail(const fs::path& file, size_t lines) {
  std::ifstream in(file);
  std::vector<std::string> all;
  for (std::string line; std::getline(in, line);)
    if (!line.empty()) all.push_back(line);
  std::string out;
  for (size_t i = all.size() > lines ? all.size() - lines : 0; i < all.size(); ++i)
    out += (out.empty() ? "" : " / ") + all[i];
  return out;
}

}  // namespace

bool isVideoPath(const fs::path& path) {
  const std::string ext = lowerExtension(path);
  return ext == ".mp4" || ext == ".mkv" || ext == ".webm";
}

std::optional<fs::path> findOnPath(const std::string& program) {
  const char* path = std::getenv("PATH");
  if (!path) return std::nullopt;
  std::stringstream folders(path);
  for (std::string folder; std::getline(folders, folder, ':');) {
    const fs::path candidate = fs::path(folder.empty() ? "." : folder) / program;
    std::error_code ec;
    if (fs::is_regular_file(candidate, ec) && ::access(candidate.c_str(), X_OK) == 0)
      return candidate;
  }
  return std::nullopt;
}

std::string videoFrameName(long frame) { return fmt::format("frame{:06d}.png", frame); }

void encodeVideo(const fs::path& ffmpeg, const fs::path& frames, double fps,
                 const fs::path& output) {
  const std::string ext = lowerExtension(output);
  // The container is named, not guessed from the name: the temporary file has another extension.
  const char* format = ext == ".webm" ? "webm" : ext == ".mkv" ? "matroska" : "mp4";
  const char* codec = ext == ".webm" ? "libvpx-vp9" : "libx264";
  const fs::path log = frames / "ffmpeg.log";
  writeFileAtomically(output, [&](const fs::path& tmp) {
    const std::vector<std::string> args = {ffmpeg.string(),
                                           "-hide_banner",
                                           "-loglevel",
                                           "error",
                                           "-nostdin",
                                           "-y",
                                           "-framerate",
                                           fmt::format("{:.9g}", fps),
                                           "-i",
                                           (frames / "frame%06d.png").string(),
                                           "-vf",
                                           "pad=ceil(iw/2)*2:ceil(ih/2)*2",
                                           "-c:v",
                                           codec,
                                           "-pix_fmt",
                                           "yuv420p",
                                           "-f",
                                           format,
                                           tmp.string()};
    std::vector<char*> argv;
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&actions, 2, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    pid_t pid = 0;
    const int spawned = posix_spawn(&pid, ffmpeg.c_str(), &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (spawned != 0)
      throw Error(fmt::format("cannot run {}: {}", ffmpeg.string(), std::strerror(spawned)));
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0)
      if (errno != EINTR)
        throw Error(fmt::format("waiting for {}: {}", ffmpeg.string(), std::strerror(errno)));
    // Ctrl-C reaches ffmpeg too (one process group): that is a cancel, not ffmpeg's failure.
    if (ProgressBar::interrupted()) throw Cancelled();
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
      const std::string how = WIFEXITED(status) ? fmt::format("exit code {}", WEXITSTATUS(status))
                                                : fmt::format("signal {}", WTERMSIG(status));
      const std::string said = tail(log, 3);
      throw Error(fmt::format("ffmpeg failed ({}){}", how, said.empty() ? "" : ": " + said));
    }
  });
}

}  // namespace luxel::cli
