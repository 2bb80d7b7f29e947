#include <gtest/gtest.h>

#include "view/frame_chart.h"
#include "view/view_status.h"

namespace tuneray {
namespace {

TEST(FrameChart, PointsAreRightAlignedOnTheScale) {
  FrameChart chart(5);
  chart.add(10);
  chart.add(30, FrameKind::kSearch);
  chart.add(20);
  // The slowest frame (30) is above the budget (25): the scale is 1.2 x 30.
  EXPECT_DOUBLE_EQ(chart.scale_ms(25), 36);
  std::vector<ChartPoint> p = chart.points(25);
  ASSERT_EQ(p.size(), 3u);
  EXPECT_FLOAT_EQ(p[0].x, 0.5f);
  EXPECT_FLOAT_EQ(p[1].x, 0.75f);
  EXPECT_FLOAT_EQ(p[2].x, 1.0f);
  EXPECT_FLOAT_EQ(p[0].y, 10.0f / 36);
  EXPECT_FLOAT_EQ(p[1].y, 30.0f / 36);
  EXPECT_EQ(p[0].kind, FrameKind::kPlain);
  EXPECT_EQ(p[1].kind, FrameKind::kSearch);
  EXPECT_FLOAT_EQ(chart.budget_y(25), 25.0f / 36);
  // A budget above every frame sets the scale.
  EXPECT_DOUBLE_EQ(chart.scale_ms(50), 60);
}

TEST(FrameChart, KeepsOnlyTheNewestFrames) {
  FrameChart chart(3);
  for (double ms : {1.0, 2.0, 3.0, 4.0, 5.0})
    chart.add(ms, ms == 3.0 ? FrameKind::kYardstick : FrameKind::kExploit);
  ASSERT_EQ(chart.size(), 3u);
  std::vector<ChartPoint> p = chart.points(0);
  EXPECT_FLOAT_EQ(p[0].x, 0.0f);
  EXPECT_FLOAT_EQ(p[0].y, 3.0f / 6);
  EXPECT_FLOAT_EQ(p[2].y, 5.0f / 6);
  EXPECT_EQ(p[0].kind, FrameKind::kYardstick);
  EXPECT_EQ(p[2].kind, FrameKind::kExploit);
  chart.clear();
  EXPECT_TRUE(chart.points(10).empty());
}

TEST(ViewStatus, TitleShowsSpeedSamplesAndSwitches) {
  ViewStatus s;
  s.scene = "cornell";
  s.frame_ms = 25;
  s.render_ms = 22.5;
  s.frame_spp = 2.5;
  s.film_spp = 40;
  s.adaptive = true;
  s.sampler = "bluenoise";
  s.accel = "native";
  EXPECT_EQ(format_title(s),
            "cornell | 25.0 ms/frame (40.0 fps, render 22.5 ms) | 2.50 spp/frame, 40.0 spp | "
            "adaptive, bluenoise | native");
}

}  // namespace
}  // namespace tuneray
