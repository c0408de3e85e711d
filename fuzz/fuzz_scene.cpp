// libFuzzer target: io::loadScene on arbitrary bytes. Accepts or throws io::InputError.
#include "fuzz/fuzz_support.h"
#include "io/scene.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return rockmass::fuzz::readInput(data, size, ".yaml", [](const std::filesystem::path& path) {
    const rockmass::io::Scene scene = rockmass::io::loadScene(path);
    (void)scene;
  });
}
