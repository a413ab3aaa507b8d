// SPDX-License-Identifier: BSD-3-Clause
// The fuzz targets' properties on their seed corpora and on every former finding
// (Testing/Data/Fuzz/regressions/<target>/): a finding fixed stays fixed. A failed
// property aborts, so a regression shows as a crashed test naming the input.
#include "PiFuzzTargets.h"

#include <gtest/gtest.h>

#include <dirent.h>

#include <fstream>
#include <iostream>
#include <iterator>
#include <string>
#include <vector>

namespace
{
std::vector<std::string> Files(const std::string& dir)
{
  std::vector<std::string> files;
  if (DIR* d = opendir(dir.c_str()))
  {
    while (dirent* e = readdir(d))
    {
      const std::string name = e->d_name;
      if (name != "." && name != ".." && name != "README.md")
      {
        files.push_back(dir + "/" + name);
      }
    }
    closedir(d);
  }
  return files;
}

// Runs `target` on every file of the directories; returns the number of inputs.
size_t Replay(void (*target)(const uint8_t*, size_t), const std::vector<std::string>& dirs)
{
  size_t count = 0;
  for (const std::string& dir : dirs)
  {
    for (const std::string& file : Files(dir))
    {
      std::ifstream in(file, std::ios::binary);
      const std::string bytes(
        (std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
      std::cout << "replaying " << file << std::endl;
      target(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size());
      ++count;
    }
  }
  return count;
}

const std::string Data = PISURF_DATA_DIR;
}

TEST(FuzzRegression, Model)
{
  EXPECT_GT(
    Replay(pisurf::fuzz::Model, { Data + "/Models", Data + "/Fuzz/regressions/model" }), 10u);
}

TEST(FuzzRegression, Expression)
{
  EXPECT_GT(Replay(pisurf::fuzz::Expression,
              { Data + "/Fuzz/expression", Data + "/Fuzz/regressions/expression" }),
    10u);
}

TEST(FuzzRegression, Molecule)
{
  EXPECT_GT(Replay(pisurf::fuzz::Molecule,
              { Data + "/Fuzz/molecule", Data + "/Fuzz/regressions/molecule" }),
    5u);
}
