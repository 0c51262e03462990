// What --resume rests on: the step control continues from a restored state
// exactly as it would have, and the checkpoint files read back bit for bit.
#include <piezocontact/output.h>
#include <piezocontact/step_control.h>

#include <filesystem>
#include <gtest/gtest.h>
#include <random>
#include <vector>

namespace
{
/// (t, k) of every try until done, rejecting the tries listed
std::vector<std::pair<double, double>> tries(piezocontact::StepControl& s,
                                             const std::vector<int>& rejected, int first = 0)
{
  std::vector<std::pair<double, double>> out;
  for (int i = first; !s.done(); ++i)
  {
    out.push_back(s.attempt());
    if (std::find(rejected.begin(), rejected.end(), i) != rejected.end())
      s.reject();
    else
      s.accept();
  }
  return out;
}
} // namespace

TEST(StepControl, RestoredAfterAnyAcceptedStepContinuesTheSame)
{
  // tries 0-2 fail (k = T/N / 8 kept until the first nominal time), 9 and 10 too
  const std::vector<int> rejected = {0, 1, 2, 9, 10};
  piezocontact::StepControl reference(1.0, 7, 4);
  const auto all = tries(reference, rejected);
  piezocontact::StepControl run(1.0, 7, 4);
  for (int i = 0; !run.done(); ++i)
  {
    run.attempt();
    if (std::find(rejected.begin(), rejected.end(), i) != rejected.end())
    {
      run.reject();
      continue;
    }
    run.accept();
    piezocontact::StepControl resumed(1.0, 7, 4);
    resumed.restore(run.nominal_steps(), run.t, run.k, run.k_last, run.accepted);
    const auto rest = tries(resumed, rejected, i + 1);
    ASSERT_EQ(rest.size(), all.size() - i - 1) << "restored after try " << i;
    for (std::size_t j = 0; j < rest.size(); ++j)
    {
      EXPECT_EQ(rest[j].first, all[i + 1 + j].first);
      EXPECT_EQ(rest[j].second, all[i + 1 + j].second);
    }
    EXPECT_EQ(resumed.accepted, reference.accepted);
  }
}

TEST(Output, NpyReadsBackBitForBit)
{
  std::mt19937_64 gen(7);
  std::uniform_real_distribution<double> dist(-1e12, 1e12);
  std::vector<double> data(37 * 9);
  for (auto& v : data)
    v = dist(gen);
  data[5] = 1e-310; // subnormal
  const auto path = std::filesystem::temp_directory_path() / "piezo_restart_test.npy";
  piezocontact::write_npy(path, data, 37, 9);
  const auto [back, rows, cols] = piezocontact::read_npy(path);
  EXPECT_EQ(rows, 37u);
  EXPECT_EQ(cols, 9u);
  EXPECT_EQ(back, data);
  std::filesystem::remove(path);
}

TEST(Output, AtomicWriteLeavesNoPartialFile)
{
  const auto dir = std::filesystem::temp_directory_path() / "piezo_atomic_test";
  std::filesystem::create_directories(dir);
  piezocontact::write_json_atomic(dir / "a.json", {{"x", 1}});
  // a directory that does not exist: the error names the file, nothing is left
  try
  {
    piezocontact::write_json_atomic(dir / "missing" / "b.json", {{"x", 2}});
    FAIL() << "no OutputError";
  }
  catch (const piezocontact::OutputError& e)
  {
    EXPECT_EQ(std::string(e.what()),
              "cannot write " + (dir / "missing" / "b.json").string()
                  + ": No such file or directory");
  }
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir),
                          std::filesystem::directory_iterator()),
            1);
  std::filesystem::remove_all(dir);
}
