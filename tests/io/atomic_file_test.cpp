#include "io/atomic_file.h"

#include <gtest/gtest.h>
#include <unistd.h>
#include <algorithm>

#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <random>
#include <set>
#include <stdexcept>
#include <string>

namespace rockmass::io {
namespace {

namespace fs = std::filesystem;
using namespace std::string_literals;

/// A fresh, empty folder per test, removed afterwards.
class AtomicFileTest : public ::testing::Test {
 protected:
  /// Creates the folder, named after the test and the process so parallel runs do not meet.
  void SetUp() override {
    const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
    folder = fs::temp_directory_path() /
             ("rockmass_" + std::string(info->name()) + "_" + std::to_string(::getpid()));
    fs::remove_all(folder);
    fs::create_directories(folder);
  }
  /// Removes the folder and everything in it.
  void TearDown() override { fs::remove_all(folder); }

  /// Names of the entries of the folder (temporaries included: they start with '.').
  std::set<std::string> entries() const {
    std::set<std::string> names;
    for (const fs::directory_entry& entry : fs::directory_iterator(folder)) {
      names.insert(entry.path().filename().string());
    }
    return names;
  }

  fs::path folder;
};

/// The bytes of a file.
std::string readBytes(const fs::path& path) {
  std::ifstream stream(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(stream), std::istreambuf_iterator<char>()};
}

TEST_F(AtomicFileTest, WritesContentExactly) {
  // NUL, CR LF and a byte above 127 would be altered by a text-mode or C-string writer.
  const std::string content = "id,x\r\n1,0.1\n\0\xff end"s;
  writeFileAtomically(folder / "out.csv", content);
  EXPECT_EQ(readBytes(folder / "out.csv"), content);
  EXPECT_EQ(entries(), std::set<std::string>{"out.csv"});
}

TEST_F(AtomicFileTest, StreamedFileAppearsOnlyWhenCommitted) {
  // A long run's history: written as it goes under a temporary name, renamed at the end;
  // a run that stops before (an exception, Ctrl-C) leaves nothing.
  {
    StreamedFile file(folder / "history.csv");
    file.write("time,u\n");
    file.write("0,0\n");
    EXPECT_EQ(entries().size(), 1u);
    EXPECT_EQ(entries().begin()->rfind(".history.csv.tmp.", 0), 0u) << *entries().begin();
  }
  EXPECT_TRUE(entries().empty());
  StreamedFile file(folder / "history.csv");
  for (int i = 0; i < 100000; ++i) file.write("1,2\n");
  file.commit();
  EXPECT_EQ(entries(), std::set<std::string>{"history.csv"});
  EXPECT_EQ(readBytes(folder / "history.csv").size(), 400000u);
  const std::vector<fs::path> written = filesWritten();
  EXPECT_NE(std::find(written.begin(), written.end(), folder / "history.csv"), written.end());
  EXPECT_THROW(file.write("late\n"), std::logic_error);
}

TEST_F(AtomicFileTest, ReplacesAnExistingFile) {
  writeFileAtomically(folder / "out.txt", "a longer first version\n");
  writeFileAtomically(folder / "out.txt", "short\n");
  EXPECT_EQ(readBytes(folder / "out.txt"), "short\n");
  EXPECT_EQ(entries(), std::set<std::string>{"out.txt"});
}

TEST_F(AtomicFileTest, MissingFolderThrowsAndLeavesNothing) {
  const fs::path target = folder / "missing" / "out.txt";
  try {
    writeFileAtomically(target, "content");
    FAIL() << "expected std::runtime_error";
  } catch (const std::runtime_error& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find(target.string()), std::string::npos) << message;
    EXPECT_NE(message.find("No such file or directory"), std::string::npos) << message;
  }
  EXPECT_TRUE(entries().empty());  // no "missing" folder, no file, no temporary
}

TEST_F(AtomicFileTest, FailedRenameRemovesTheTemporary) {
  // The temporary is written, but a non-empty folder cannot be replaced by a file.
  fs::create_directories(folder / "out.txt" / "inside");
  EXPECT_THROW(writeFileAtomically(folder / "out.txt", "content"), std::runtime_error);
  EXPECT_EQ(entries(), std::set<std::string>{"out.txt"});
  EXPECT_TRUE(fs::is_directory(folder / "out.txt"));
}

TEST_F(AtomicFileTest, WriterGetsATemporaryBesideTheTarget) {
  // A writer that opens the file itself (as OpenVDB does) writes the temporary, which then
  // becomes the target.
  fs::path seen;
  writeAtomically(folder / "grid.vdb", [&](const fs::path& temporary) {
    seen = temporary;
    std::ofstream(temporary, std::ios::binary) << "vdb";
  });
  EXPECT_EQ(seen.parent_path(), folder);
  EXPECT_NE(seen, folder / "grid.vdb");
  EXPECT_EQ(readBytes(folder / "grid.vdb"), "vdb");
  EXPECT_EQ(entries(), std::set<std::string>{"grid.vdb"});
}

TEST_F(AtomicFileTest, FailingWriterLeavesNothingAndNamesThePath) {
  // The old file survives, the half-written temporary goes, the message says which file.
  writeFileAtomically(folder / "grid.vdb", "old");
  try {
    writeAtomically(folder / "grid.vdb", [](const fs::path& temporary) {
      std::ofstream(temporary, std::ios::binary) << "half";
      throw std::runtime_error("disk full");
    });
    FAIL() << "expected std::runtime_error";
  } catch (const std::runtime_error& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find((folder / "grid.vdb").string()), std::string::npos) << message;
    EXPECT_NE(message.find("disk full"), std::string::npos) << message;
  }
  EXPECT_EQ(readBytes(folder / "grid.vdb"), "old");
  EXPECT_EQ(entries(), std::set<std::string>{"grid.vdb"});
}

TEST(FormatDouble, GivesTheShortestForms) {
  EXPECT_EQ(formatDouble(0.1), "0.1");
  EXPECT_EQ(formatDouble(1e21), "1e+21");
  EXPECT_EQ(formatDouble(3.0), "3");
  EXPECT_EQ(formatDouble(-2.5), "-2.5");
  EXPECT_EQ(formatDouble(0.0), "0");
  EXPECT_EQ(formatDouble(-0.0), "-0");
  EXPECT_EQ(formatDouble(1.0 / 3.0), "0.3333333333333333");
  EXPECT_EQ(formatDouble(5e-324), "5e-324");
  EXPECT_EQ(formatDouble(std::numeric_limits<double>::quiet_NaN()), "nan");
  EXPECT_EQ(formatDouble(-std::numeric_limits<double>::quiet_NaN()), "nan");
  EXPECT_EQ(formatDouble(std::numeric_limits<double>::infinity()), "inf");
  EXPECT_EQ(formatDouble(-std::numeric_limits<double>::infinity()), "-inf");
}

TEST(FormatDouble, RoundTripsRandomDoubles) {
  // Random bit patterns cover every exponent, subnormals and both zeros; plain uniform
  // values cover the ordinary numbers of coordinates. Comparing bits also tells -0 from 0.
  std::mt19937_64 random(20131001);
  std::uniform_real_distribution<double> uniform(-1e4, 1e4);
  int checked = 0;
  while (checked < 10000) {
    const double value = checked % 2 == 0 ? std::bit_cast<double>(random()) : uniform(random);
    if (!std::isfinite(value)) continue;  // about 1 in 2048 random bit patterns
    const std::string text = formatDouble(value);
    double parsed = 0.0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), parsed);
    ASSERT_EQ(error, std::errc()) << text;
    ASSERT_EQ(end, text.data() + text.size()) << text;
    ASSERT_EQ(std::bit_cast<std::uint64_t>(parsed), std::bit_cast<std::uint64_t>(value)) << text;
    ++checked;
  }
}

}  // namespace
}  // namespace rockmass::io
