// Macro F1, accuracy and the confusion matrix against hand computation.
#include <gtest/gtest.h>

#include "har/har_internal.hpp"
#include "ptnet/error.hpp"
#include "ptnet/har.hpp"

using namespace ptnet::har;

namespace {
// Expands a confusion matrix (row = true, col = predicted) into label lists.
void expand(const std::vector<std::vector<int>>& m, std::vector<int>& t, std::vector<int>& p) {
  for (int i = 0; i < int(m.size()); ++i)
    for (int j = 0; j < int(m[i].size()); ++j)
      for (int k = 0; k < m[i][j]; ++k) {
        t.push_back(i);
        p.push_back(j);
      }
}
}  // namespace

TEST(HarMetrics, MacroF1OfAKnownConfusionMatrix) {
  // true\pred  0  1  2
  //   0        5  1  0
  //   1        2  3  1
  //   2        0  0  4
  // class 0: tp 5, actual 6, predicted 7 -> F1 = 10/13
  // class 1: tp 3, actual 6, predicted 4 -> F1 = 6/10
  // class 2: tp 4, actual 4, predicted 5 -> F1 = 8/9
  std::vector<int> t, p;
  expand({{5, 1, 0}, {2, 3, 1}, {0, 0, 4}}, t, p);
  ClassificationReport r = classification_report(t, p, 3);
  EXPECT_EQ(r.confusion(0, 0), 5);
  EXPECT_EQ(r.confusion(1, 0), 2);
  EXPECT_EQ(r.confusion(1, 2), 1);
  EXPECT_NEAR(r.f1[0], 10.0 / 13.0, 1e-12);
  EXPECT_NEAR(r.f1[1], 0.6, 1e-12);
  EXPECT_NEAR(r.f1[2], 8.0 / 9.0, 1e-12);
  EXPECT_NEAR(r.macro_f1, (10.0 / 13.0 + 0.6 + 8.0 / 9.0) / 3.0, 1e-12);
  EXPECT_NEAR(r.accuracy, 12.0 / 16.0, 1e-12);
  EXPECT_NEAR(r.precision[0], 5.0 / 7.0, 1e-12);
  EXPECT_NEAR(r.recall[1], 0.5, 1e-12);
  EXPECT_EQ(r.support[2], 4);
}

TEST(HarMetrics, AbsentClassesAreLeftOutPredictedOnlyClassesCountAsZero) {
  // 4 classes; class 3 never occurs; class 2 is only predicted.
  std::vector<int> t = {0, 0, 1, 1};
  std::vector<int> p = {0, 0, 1, 2};
  ClassificationReport r = classification_report(t, p, 4);
  EXPECT_FALSE(r.present[3]);
  EXPECT_TRUE(r.present[2]);
  EXPECT_EQ(r.f1[2], 0.0);
  // F1: class 0 = 1, class 1 = 2*1/(2+1) = 2/3, class 2 = 0 -> mean over 3.
  EXPECT_NEAR(r.macro_f1, (1.0 + 2.0 / 3.0 + 0.0) / 3.0, 1e-12);
  EXPECT_NEAR(r.accuracy, 0.75, 1e-12);
}

TEST(HarMetrics, BadInputIsAnError) {
  EXPECT_THROW(classification_report({0, 1}, {0}, 2), ptnet::Error);
  EXPECT_THROW(classification_report({}, {}, 2), ptnet::Error);
  try {
    classification_report({0, 5}, {0, 1}, 2);
    FAIL();
  } catch (const ptnet::Error& e) {
    EXPECT_STREQ(e.what(), "metrics: label 5 outside 0..1");
  }
}
