// libFuzzer target: io::readFab on arbitrary bytes. Accepts or throws io::InputError.
#include "fuzz/fuzz_support.h"
#include "io/fab.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return rockmass::fuzz::readInput(data, size, ".fab", [](const std::filesystem::path& path) {
    const rockmass::io::FabFile fab = rockmass::io::readFab(path);
    (void)fab;
  });
}
