#include "swath/geometry/capped_heap.hpp"

#include <gtest/gtest.h>

#include <functional>
#include <queue>
#include <random>
#include <utility>
#include <vector>

namespace swath::geometry {
namespace {

using Item = std::pair<int, int>;  // key, id

struct ByKeyOfInt {
  double operator()(int item) const { return item; }
};

// A lead key as a search's is (its first field): items of equal keys compared whole.
struct ByKey {
  double operator()(const Item& item) const { return item.first; }
};

// The items as one std::priority_queue gives them (the brute force), against CappedHeap, on
// random runs of pushes and pops (fixed seed): keys from a small range, so that many are equal and
// items land on both sides of the cap after each refill; ids tell equal keys apart (mostly).
// Without a lead key and with one.
template <class Lead>
void expect_the_order_of_one_heap(unsigned seed) {
  std::mt19937 random(seed);
  for (int run = 0; run < 200; ++run) {
    CappedHeap<Item, Lead> capped;
    capped.clear({-1, 0});
    std::priority_queue<Item, std::vector<Item>, std::greater<>> heap;
    const int keys = 1 + int(random() % 2000);
    const int steps = int(random() % 3000);
    const unsigned pop_per_mille = 50 + random() % 600;
    int low = 0;  // keys pushed are >= the last popped one, as in an A* search
    for (int step = 0; step < steps; ++step) {
      if (!heap.empty() && random() % 1000 < pop_per_mille) {
        ASSERT_FALSE(capped.empty());
        const Item got = capped.pop();
        ASSERT_EQ(got, heap.top()) << "run " << run << " step " << step;
        heap.pop();
        low = got.first;
      } else {
        // Ids in no order: an item of the cap's key may come before or after it.
        const Item item{low + int(random() % unsigned(keys)), int(random() % 100000)};
        capped.push(item);
        heap.push(item);
      }
    }
    while (!heap.empty()) {
      ASSERT_EQ(capped.pop(), heap.top()) << "run " << run;
      heap.pop();
    }
    EXPECT_TRUE(capped.empty());
  }
}

TEST(CappedHeap, GivesItemsInTheOrderOfOneHeap) {
  expect_the_order_of_one_heap<NoLead>(52);
}

TEST(CappedHeap, GivesItemsInTheOrderOfOneHeapByTheirLeadKeys) {
  expect_the_order_of_one_heap<ByKey>(53);
}

// Keys below the last one popped (a search need not push in order) still come out least first.
TEST(CappedHeap, TakesItemsBelowTheCap) {
  CappedHeap<int, ByKeyOfInt> capped;
  capped.clear(-1);
  for (int k = 1000; k > 0; --k) capped.push(k);
  EXPECT_EQ(capped.pop(), 1);
  capped.push(0);
  capped.push(5000);
  EXPECT_EQ(capped.pop(), 0);
  for (int k = 2; k <= 1000; ++k) ASSERT_EQ(capped.pop(), k);
  EXPECT_EQ(capped.pop(), 5000);
  EXPECT_TRUE(capped.empty());
}

}  // namespace
}  // namespace swath::geometry
