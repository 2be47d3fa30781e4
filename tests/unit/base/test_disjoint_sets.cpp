// Disjoint sets united from every core: the sets and their numbering must not depend on the order
// of the unions or the number of threads.
#include <gtest/gtest.h>

#include <vector>

#include "reliefkit/base/disjoint_sets.h"

using namespace reliefkit;

TEST(DisjointSets, LongChainsAreNumberedByTheirLowestElement) {
  // {0, 1}, then evens and odds from 2 up, each united to its neighbour two up from the top down:
  // every union links a root under the next lower one, so each of those sets is one long chain
  // before numbering, and their numbers (1 and 2) are not their roots (2 and 3).
  const int n = 20001;
  DisjointSets sets(n);
  sets.unite(0, 1);
  for (int i = n - 3; i >= 2; --i) sets.unite(i, i + 2);
  int count = -1;
  const std::vector<int> set = std::move(sets).numbered(count);
  ASSERT_EQ(count, 3);
  EXPECT_EQ(set[0], 0);
  EXPECT_EQ(set[1], 0);
  for (int i = 2; i < n; ++i) ASSERT_EQ(set[size_t(i)], i % 2 == 0 ? 1 : 2) << i;
}

TEST(DisjointSets, ParallelUnionsGiveTheSerialSets) {
  // Element i united with i + 7 where i % 3 != 0 (chains broken every third step): the parallel
  // result must equal the serial one element for element.
  const int n = 100000;
  auto build = [n](bool parallel) {
    DisjointSets sets(n);
#pragma omp parallel for schedule(dynamic, 64) if (parallel)
    for (int i = 0; i < n - 7; ++i)
      if (i % 3 != 0) sets.unite(i + 7, i);
    int count = 0;
    std::vector<int> set = std::move(sets).numbered(count);
    set.push_back(count);
    return set;
  };
  EXPECT_EQ(build(true), build(false));
}
