// SPDX-License-Identifier: BSD-3-Clause
// The marching-cubes polygons of each case, built once from
// vtkMarchingCubesTriangleCases.
#include "PiPolygonTable.h"

#include "vtkMarchingCubesTriangleCases.h"

#include <algorithm>
#include <functional>
#include <utility>

namespace pisurf
{
namespace triangulator
{

const std::array<std::vector<std::vector<int>>, 256>& PolygonTable()
{
  static const std::array<std::vector<std::vector<int>>, 256> table = []
  {
    std::array<std::vector<std::vector<int>>, 256> t;
    vtkMarchingCubesTriangleCases* cases = vtkMarchingCubesTriangleCases::GetCases();
    for (int index = 0; index < 256; ++index)
    {
      std::vector<std::array<int, 3>> tris;
      for (const int* e = cases[index].edges; *e >= 0; e += 3)
      {
        tris.push_back({ e[0], e[1], e[2] });
      }
      const int k = static_cast<int>(tris.size());
      std::vector<int> group(k);
      for (int a = 0; a < k; ++a)
      {
        group[a] = a;
      }
      std::function<int(int)> root = [&](int a) { return group[a] == a ? a : root(group[a]); };
      for (int a = 0; a < k; ++a)
      {
        for (int b = a + 1; b < k; ++b)
        {
          int shared = 0;
          for (int x : tris[a])
          {
            shared += std::count(tris[b].begin(), tris[b].end(), x) ? 1 : 0;
          }
          if (shared == 2)
          {
            group[root(b)] = root(a);
          }
        }
      }
      for (int g = 0; g < k; ++g)
      {
        if (root(g) != g)
        {
          continue;
        }
        // Sides used once in the group form its outline.
        std::vector<std::pair<int, int>> sides;
        for (int a = 0; a < k; ++a)
        {
          if (root(a) != g)
          {
            continue;
          }
          for (int c = 0; c < 3; ++c)
          {
            sides.emplace_back(tris[a][c], tris[a][(c + 1) % 3]);
          }
        }
        std::vector<std::pair<int, int>> outline;
        for (const auto& x : sides)
        {
          int uses = 0;
          for (const auto& y : sides)
          {
            uses += (x == y || (x.first == y.second && x.second == y.first)) ? 1 : 0;
          }
          if (uses == 1)
          {
            outline.push_back(x);
          }
        }
        std::vector<int> cycle{ outline.empty() ? -1 : outline[0].first };
        bool disk = !outline.empty();
        while (disk && cycle.size() < outline.size())
        {
          int next = -1;
          for (const auto& x : outline)
          {
            const int from = cycle.back();
            const int previous = cycle.size() > 1 ? cycle[cycle.size() - 2] : -1;
            const int other = x.first == from ? x.second : x.second == from ? x.first : -1;
            if (other >= 0 && other != previous && other != cycle[0])
            {
              next = other;
              break;
            }
          }
          disk = next >= 0;
          cycle.push_back(next);
        }
        if (disk && cycle.size() == outline.size())
        {
          t[index].push_back(cycle);
        }
        else
        {
          for (int a = 0; a < k; ++a)
          {
            if (root(a) == g)
            {
              t[index].push_back({ tris[a][0], tris[a][1], tris[a][2] });
            }
          }
        }
      }
    }
    return t;
  }();
  return table;
}

} // namespace triangulator
} // namespace pisurf
