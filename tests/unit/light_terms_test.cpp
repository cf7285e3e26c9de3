// The light terms' names (planet/renderer.hpp, parse_light_terms): what `render --terms` and a
// suite's terms parse, and what they refuse.
#include <gtest/gtest.h>

#include <string>

#include "thalassa/planet/renderer.hpp"

namespace thalassa {
namespace {

LightTerms parsed(const std::string& text) {
  LightTerms terms;
  const std::string problem = parse_light_terms(text, terms);
  EXPECT_EQ(problem, "") << text;
  return terms;
}

TEST(LightTerms, AnySubsetInAnyOrder) {
  const LightTerms all = parsed("sun,sky,sea,air");
  EXPECT_TRUE(all.sun && all.sky && all.sea && all.air);
  const LightTerms two = parsed("sea,sun");
  EXPECT_TRUE(two.sun && two.sea);
  EXPECT_FALSE(two.sky || two.air);
  const LightTerms one = parsed("air");
  EXPECT_TRUE(one.air);
  EXPECT_FALSE(one.sun || one.sky || one.sea);
  const LightTerms again = parsed("sky,sky");  // named twice: once
  EXPECT_TRUE(again.sky);
  EXPECT_FALSE(again.sun || again.sea || again.air);
  const LightTerms trailing = parsed("sun,");  // a comma at the end opens no item
  EXPECT_TRUE(trailing.sun);
  EXPECT_FALSE(trailing.sky);
}

TEST(LightTerms, RefusesUnknownEmptyAndMisplacedItems) {
  LightTerms terms;
  EXPECT_EQ(parse_light_terms("sun,moon", terms),
            "expected a comma-separated subset of sun, sky, sea, air, got \"moon\"");
  EXPECT_EQ(parse_light_terms("Sun", terms),
            "expected a comma-separated subset of sun, sky, sea, air, got \"Sun\"");
  EXPECT_EQ(parse_light_terms("sun, sky", terms),  // no spaces
            "expected a comma-separated subset of sun, sky, sea, air, got \" sky\"");
  EXPECT_EQ(parse_light_terms("sun,,sky", terms),
            "expected a comma-separated subset of sun, sky, sea, air, got \"\"");
  EXPECT_EQ(parse_light_terms(",", terms),
            "expected a comma-separated subset of sun, sky, sea, air, got \"\"");
  EXPECT_EQ(parse_light_terms("", terms), "expected at least one of sun, sky, sea, air");
}

}  // namespace
}  // namespace thalassa
