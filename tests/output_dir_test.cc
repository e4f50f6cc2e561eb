// OutputDir: all-or-nothing output into a folder that may not exist yet.
#include "femup/reporting/output_dir.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "femup/core/errors.h"
#include "scratch_dir.h"

namespace femup {
namespace {

namespace fs = std::filesystem;
using testing::ScratchDir;

TEST(OutputDir, CreatesMissingParentFoldersOnCommit) {
  ScratchDir dir;
  const std::string target = dir.File("a/b/c");
  {
    OutputDir out(target);
    out.WriteText("result.json", "{}\n");
    out.Commit();
  }
  EXPECT_TRUE(fs::is_regular_file(target + "/result.json"));
  // Only the committed file is there: no staging folder left.
  int entries = 0;
  for (const auto& e : fs::directory_iterator(target)) {
    EXPECT_EQ(e.path().filename(), "result.json");
    ++entries;
  }
  EXPECT_EQ(entries, 1);
}

TEST(OutputDir, RemovesTheFoldersItCreatedWhenNotCommitted) {
  ScratchDir dir;
  {
    OutputDir out(dir.File("a/b/c"));
    out.WriteText("result.json", "{}\n");
  }
  EXPECT_FALSE(fs::exists(dir.File("a")));
  EXPECT_TRUE(fs::is_empty(dir.path()));
}

TEST(OutputDir, LeavesExistingFoldersAndTheirFilesAlone) {
  ScratchDir dir;
  fs::create_directories(dir.File("a"));
  std::ofstream(dir.File("a/old.txt")) << "kept";
  {
    OutputDir out(dir.File("a"));
    out.WriteText("old.txt", "new");
  }  // not committed
  std::ifstream in(dir.File("a/old.txt"));
  std::string text;
  in >> text;
  EXPECT_EQ(text, "kept");
  { OutputDir out(dir.File("a/b")); }  // not committed: b removed, a kept
  EXPECT_TRUE(fs::is_directory(dir.File("a")));
  EXPECT_FALSE(fs::exists(dir.File("a/b")));
}

TEST(OutputDir, RefusesAFileInThePathAndNamesIt) {
  ScratchDir dir;
  std::ofstream(dir.File("file")) << "x";
  try {
    OutputDir out(dir.File("file/sub"));
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("file/sub"), std::string::npos) << e.what();
  }
  try {
    OutputDir out(dir.File("file"));
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("a file of that name exists"), std::string::npos)
        << e.what();
  }
  EXPECT_TRUE(fs::is_regular_file(dir.File("file")));
}

TEST(OutputDir, RefusesAnEmptyName) { EXPECT_THROW(OutputDir out(""), InputError); }

}  // namespace
}  // namespace femup
