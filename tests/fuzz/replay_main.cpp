// The fuzz targets without libFuzzer: runs LLVMFuzzerTestOneInput once on every file given
// (or in every folder given), as `make test` does over the checked-in corpora, and fails if
// one takes longer than the stated seconds (a hang is a finding too).
//   replay TIMEOUT_SECONDS PATH...
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace {

std::vector<std::filesystem::path> inputs(int argc, char** argv) {
  std::vector<std::filesystem::path> files;
  for (int i = 2; i < argc; ++i) {
    const std::filesystem::path p = argv[i];
    if (std::filesystem::is_directory(p)) {
      for (const auto& e : std::filesystem::recursive_directory_iterator(p)) {
        if (e.is_regular_file()) files.push_back(e.path());
      }
    } else {
      files.push_back(p);
    }
  }
  return files;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: %s TIMEOUT_SECONDS PATH...\n", argv[0]);
    return 2;
  }
  const double timeout = std::atof(argv[1]);
  double slowest = 0;
  std::string slowestName;
  const std::vector<std::filesystem::path> files = inputs(argc, argv);
  for (const std::filesystem::path& file : files) {
    std::ifstream in(file, std::ios::binary);
    const std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const auto start = std::chrono::steady_clock::now();
    LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (seconds > slowest) {
      slowest = seconds;
      slowestName = file.string();
    }
    if (seconds > timeout) {
      std::fprintf(stderr, "FAIL: %s took %.1f s (limit %.0f s)\n", file.string().c_str(), seconds, timeout);
      return 1;
    }
  }
  std::printf("%zu inputs replayed; slowest %.3f s (%s)\n", files.size(), slowest, slowestName.c_str());
  return files.empty() ? 1 : 0;
}
