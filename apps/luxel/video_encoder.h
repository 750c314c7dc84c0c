// `luxel animate -o movie.mp4`: frames into a video through ffmpeg, which luxel does not link but
// runs, when it is on PATH (Debian's package `ffmpeg`; scripts/install-deps.sh installs it).
#pragma once

#include <filesystem>
#include <optional>
#include <string>

namespace luxel::cli {

// Whether `path` names a video luxel can write: .mp4 (H.264), .mkv (H.264 in Matroska) or .webm
// (VP9).
bool isVideoPath(const std::filesystem::path& path);

// The first executable `program` in the folders of $PATH; none when there is none.
std::optional<std::filesystem::path> findOnPath(const std::string& program);

// Encodes the PNG frames `frames`/frame000000.png, frame000001.png, ... at `fps` frames a second
// into `output` with `ffmpeg`, 8-bit 4:2:0 (an odd side is padded by a pixel, as 4:2:0 needs even
// sides), written to a temporary file and renamed. Throws Error naming `output` with ffmpeg's
// last words when it fails, Cancelled when Ctrl-C stopped it.
void encodeVideo(const std::filesystem::path& ffmpeg, const std::filesystem::path& frames,
                 double fps, const std::filesystem::path& output);

// The name of frame `frame` in the folder encodeVideo reads.
std::string videoFrameName(long frame);

}  // namespace luxel::cli
