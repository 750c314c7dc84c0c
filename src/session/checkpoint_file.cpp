#include "session/checkpoint_file.h"

#include <cstring>
#include <fstream>

#include <fmt/format.h>

#include "core/content_hash.h"
#include "io/atomic_file.h"
#include "io/input_file.h"
#include "luxel/checkpoint.h"
#include "luxel/error.h"

namespace luxel {
namespace {

constexpr char kMagic[8] = {'L', 'U', 'X', 'E', 'L', 'C', 'K', 'P'};
constexpr uint32_t kFormat = 1;

struct Header {
  char magic[8];
  uint32_t format;
  uint32_t reserved;
  uint64_t key;
  uint64_t payloadBytes;
  uint64_t payloadChecksum;
};

uint64_t checksum(std::span<const std::byte> payload) {
  ContentHash h;
  h.bytes(payload.data(), payload.size());
  return h.digest();
}

}  // namespace

void writeCheckpointFile(const std::filesystem::path& path, uint64_t key, std::span<const std::byte> payload) {
  Header h{};
  std::memcpy(h.magic, kMagic, sizeof kMagic);
  h.format = kFormat;
  h.key = key;
  h.payloadBytes = payload.size();
  h.payloadChecksum = checksum(payload);
  writeFileAtomically(path, [&](const std::filesystem::path& tmp) {
    OutputFile out(tmp);
    out.write(&h, sizeof h);
    out.write(payload.data(), payload.size());
    out.close();
  });
}

std::vector<std::byte> readCheckpointFile(const std::filesystem::path& path, uint64_t key) {
  const std::string name = path.string();
  if (const std::optional<std::string> why = whyNotARegularFile(path)) throw Error(fmt::format("checkpoint {}: {}", name, *why));
  std::error_code ec;
  const uintmax_t size = std::filesystem::file_size(path, ec);
  std::ifstream in(path, std::ios::binary);
  if (ec || !in) throw Error(fmt::format("checkpoint {}: cannot be read", name));
  Header h{};
  if (size < sizeof h || !in.read(reinterpret_cast<char*>(&h), sizeof h) || std::memcmp(h.magic, kMagic, sizeof kMagic) != 0)
    throw Error(fmt::format("checkpoint {}: not a luxel checkpoint", name));
  if (h.format != kFormat)
    throw Error(fmt::format("checkpoint {}: format {}, this luxel reads format {}", name, h.format, kFormat));
  if (h.key != key)
    throw Error(fmt::format("checkpoint {}: written for another solve (other surfaces, lights, solver, backend or "
                            "options than this run's); run with the same scene and options, or start afresh without --resume",
                            name));
  if (h.payloadBytes != size - sizeof h)
    throw Error(fmt::format("checkpoint {}: damaged: it holds {} bytes of state where its header says {}", name,
                            size - sizeof h, h.payloadBytes));
  std::vector<std::byte> payload(size_t(h.payloadBytes));
  if (!in.read(reinterpret_cast<char*>(payload.data()), std::streamsize(payload.size())))
    throw Error(fmt::format("checkpoint {}: cannot be read", name));
  if (checksum(payload) != h.payloadChecksum) throw Error(fmt::format("checkpoint {}: damaged: its checksum does not match", name));
  return payload;
}

}  // namespace luxel
