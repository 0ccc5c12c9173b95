// Readers called from several threads at once (a batch run): OpenMesh's global readers are serialised by
// our mutex, so every thread gets exactly the mesh a lone read gives. Run once under TSan/ASan.

#include "format_test_support.hpp"
#include "pdeface/core/sample_face.hpp"
#include "pdeface/off/off.hpp"
#include "pdeface/ply/ply.hpp"
#include "pdeface/stl/stl.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <functional>
#include <thread>
#include <vector>

using namespace pdeface;
using namespace pdeface::test;

namespace {

using Reader = std::function<Result<Mesh>(std::string_view)>;

struct Job {
  Reader read;
  std::string bytes;
};

// Two PLY inputs (real scans when present, else two sample faces, one binary and one ASCII).
std::vector<std::string> ply_inputs() {
  std::vector<std::string> inputs;
  for (const char* name : {"facefuns_f18.ply", "facefuns_m66.ply"})
    if (const auto path = face(name)) inputs.push_back(*read_file(*path));
  if (inputs.size() == 2) return inputs;
  return {*ply::write(sample_face()), *ply::write(sample_face({.seed = 2}), {.binary = false})};
}

} // namespace

TEST(FormatThreads, ConcurrentReadsGiveTheSameMeshes) {
  const Reader ply_read = [](std::string_view b) { return ply::read(b, "t.ply"); };
  std::vector<Job> jobs;
  for (std::string& bytes : ply_inputs())
    jobs.push_back({ply_read, std::move(bytes)});
  const Mesh small = sample_face({.spacing_mm = 2.5});
  jobs.push_back({[](std::string_view b) { return off::read(b, "t.off"); }, *off::write(small)});
  jobs.push_back({[](std::string_view b) { return stl::read(b, "t.stl"); }, *stl::write(small)});

  std::vector<Mesh> expected;
  for (const Job& job : jobs)
    expected.push_back(*job.read(job.bytes));

  std::atomic<int> mismatches{0};
  std::vector<std::thread> threads;
  for (std::size_t j = 0; j < jobs.size(); ++j)
    threads.emplace_back([&, j] {
      for (int round = 0; round < 6; ++round) {
        const Result<Mesh> mesh = jobs[j].read(jobs[j].bytes);
        if (!mesh || mesh->positions != expected[j].positions || mesh->triangles != expected[j].triangles)
          ++mismatches;
      }
    });
  for (std::thread& t : threads)
    t.join();
  EXPECT_EQ(mismatches.load(), 0);
}

// Writers share OpenMesh's singletons too.
TEST(FormatThreads, ConcurrentWritesGiveTheSameBytes) {
  const Mesh mesh = sample_face({.spacing_mm = 2.5});
  const std::string expected = *ply::write(mesh);
  std::atomic<int> mismatches{0};
  std::vector<std::thread> threads;
  for (int t = 0; t < 3; ++t)
    threads.emplace_back([&] {
      for (int round = 0; round < 6; ++round)
        if (ply::write(mesh).value() != expected) ++mismatches;
    });
  for (std::thread& t : threads)
    t.join();
  EXPECT_EQ(mismatches.load(), 0);
}
