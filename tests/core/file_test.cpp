#include "pdeface/core/file.hpp"

#include "pdeface_test.hpp"

#include <fstream>

namespace pdeface {
namespace {

std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

TEST(File, AtomicWriteCreatesAndReplaces) {
  test::TempDir dir;
  const auto path = dir / "out.bin";
  ASSERT_TRUE(write_file_atomic(path, std::string_view("first\0x", 7)).ok());
  EXPECT_EQ(slurp(path), std::string("first\0x", 7));
  ASSERT_TRUE(write_file_atomic(path, "second").ok());
  EXPECT_EQ(slurp(path), "second");
  EXPECT_EQ(dir.entries(), 1U) << "no temporary file may be left beside the output";
  auto bytes = read_file(path);
  ASSERT_TRUE(bytes.ok());
  EXPECT_EQ(*bytes, "second");
}

TEST(File, AtomicWriteIntoMissingFolderFailsAndLeavesNothing) {
  test::TempDir dir;
  auto r = write_file_atomic(dir / "no" / "such" / "out.ply", "x");
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().code, ErrorCode::Io);
  EXPECT_NE(r.error().source.find("out.ply"), std::string::npos);
  EXPECT_EQ(dir.entries(), 0U);
}

TEST(File, SeveralFilesAreWrittenAsASet) {
  test::TempDir dir;
  const OutputFile three[] = {
      {dir / "a.ply", "mesh"}, {dir / "b.json", "curves"}, {dir / "c.svg", "picture"}};
  ASSERT_TRUE(write_files_atomic(three).ok());
  EXPECT_EQ(slurp(dir / "b.json"), "curves");
  EXPECT_EQ(dir.entries(), 3U);
  // A failure after the first output (its folder is missing): none of them appears, nothing is left
  // behind, and what was there stays as it was.
  const OutputFile broken[] = {
      {dir / "a.ply", "new mesh"}, {dir / "no" / "b.json", "x"}, {dir / "d.svg", "y"}};
  const Result<void> r = write_files_atomic(broken);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().code, ErrorCode::Io);
  EXPECT_NE(r.error().source.find("b.json"), std::string::npos) << r.error().source;
  EXPECT_EQ(slurp(dir / "a.ply"), "mesh");
  EXPECT_FALSE(std::filesystem::exists(dir / "d.svg"));
  EXPECT_EQ(dir.entries(), 3U) << "no temporary file may be left";
}

TEST(File, AnAtomicFileAppearsWholeOnCommitOnly) {
  test::TempDir dir;
  const auto path = dir / "out.ply";
  ASSERT_TRUE(write_file_atomic(path, "old").ok());
  {
    Result<AtomicFile> file = AtomicFile::create(path);
    ASSERT_TRUE(file) << file.error().to_string();
    ASSERT_TRUE(file->append("new ").ok());
    ASSERT_TRUE(file->append(std::string_view("pi\0eces", 7)).ok());
    EXPECT_EQ(slurp(path), "old") << "the path keeps its old file until the commit";
    EXPECT_EQ(dir.entries(), 2U);
    AtomicFile moved = std::move(file).value(); // the temporary file goes with the object
    ASSERT_TRUE(moved.commit().ok());
    EXPECT_THROW((void)moved.commit(), std::logic_error);
    EXPECT_THROW((void)moved.append("x"), std::logic_error);
  }
  EXPECT_EQ(slurp(path), std::string("new pi\0eces", 11));
  EXPECT_EQ(dir.entries(), 1U);
  {
    Result<AtomicFile> abandoned = AtomicFile::create(path); // an error half-way: never committed
    ASSERT_TRUE(abandoned);
    ASSERT_TRUE(abandoned->append("half").ok());
  }
  EXPECT_EQ(slurp(path), std::string("new pi\0eces", 11));
  EXPECT_EQ(dir.entries(), 1U) << "no temporary file may be left";
  const Result<AtomicFile> missing = AtomicFile::create(dir / "no" / "out.ply");
  ASSERT_FALSE(missing);
  EXPECT_EQ(missing.error().code, ErrorCode::Io);
  EXPECT_EQ(dir.entries(), 1U);
}

TEST(File, AnAtomicFileCanBeWrittenOutOfOrder) {
  test::TempDir dir;
  Result<AtomicFile> file = AtomicFile::create(dir / "out.bin");
  ASSERT_TRUE(file);
  ASSERT_TRUE(file->write_at(6, "world").ok());
  ASSERT_TRUE(file->write_at(0, "hello ").ok());
  ASSERT_TRUE(file->append("hel").ok()); // appends where the appending left off: the start
  ASSERT_TRUE(file->commit().ok());
  EXPECT_EQ(slurp(dir / "out.bin"), "hello world");
  EXPECT_EQ(dir.entries(), 1U);
}

TEST(File, ReadErrorsNameTheFile) {
  test::TempDir dir;
  auto missing = read_file(dir / "absent.wrl");
  ASSERT_FALSE(missing);
  EXPECT_EQ(missing.error().code, ErrorCode::Io);
  EXPECT_NE(missing.error().to_string().find("absent.wrl: i/o error: cannot open"), std::string::npos);
  auto folder = read_file(dir.path());
  ASSERT_FALSE(folder);
  EXPECT_EQ(folder.error().message, "is a directory, not a file");
}

TEST(File, ReadsEmptyFile) {
  test::TempDir dir;
  ASSERT_TRUE(write_file_atomic(dir / "empty", "").ok());
  auto bytes = read_file(dir / "empty");
  ASSERT_TRUE(bytes.ok());
  EXPECT_TRUE(bytes->empty());
}

} // namespace
} // namespace pdeface
