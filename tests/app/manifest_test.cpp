// `discreel batch`'s manifest: words split as a shell splits them, renders picked by index.
#include <gtest/gtest.h>

#include <map>
#include <string>

#include "manifest.hpp"

namespace discreel::app {
namespace {

using Words = std::vector<std::string>;

TEST(ManifestTest, WordsSplitAsAShellSplitsThem) {
    EXPECT_EQ(*split_words("a.yaml -o out.mp4 --crf 20"),
              (Words{"a.yaml", "-o", "out.mp4", "--crf", "20"}));
    EXPECT_EQ(*split_words("  'my scene.yaml'\t-o \"out \\\"1\\\".png\" a\\ b  "),
              (Words{"my scene.yaml", "-o", "out \"1\".png", "a b"}));
    EXPECT_EQ(*split_words("''"), (Words{""}));
    EXPECT_EQ(*split_words("x\r"), (Words{"x"}));
    EXPECT_EQ(split_words("'open").error().message, "unterminated ' quote");
    EXPECT_EQ(split_words("\"open").error().message, "unterminated \" quote");
    EXPECT_EQ(split_words("end\\").error().message, "a backslash ends the line");
}

TEST(ManifestTest, RendersArePickedByIndexSkippingBlanksAndComments) {
    const std::string text = "# renders\n\na.yaml -o a.mp4\n  # later\nb.yaml -o 'b c.png'\n";
    const auto first = pick_render(text, 0, "m.txt");
    ASSERT_TRUE(first);
    EXPECT_EQ(first->number, 3);
    EXPECT_EQ(first->words, (Words{"a.yaml", "-o", "a.mp4"}));
    const auto second = pick_render(text, 1, "m.txt");
    ASSERT_TRUE(second);
    EXPECT_EQ(second->number, 5);
    EXPECT_EQ(second->words, (Words{"b.yaml", "-o", "b c.png"}));
    EXPECT_EQ(pick_render(text, 2, "m.txt").error().message,
              "index 2 is past the end of m.txt, which has 2 renders (indexes 0 to 1)");
    EXPECT_EQ(pick_render("x -o 'y\n", 0, "m.txt").error().message,
              "m.txt:1: unterminated ' quote");
    EXPECT_EQ(pick_render("# nothing\n", 0, "m.txt").error().message,
              "index 0 is past the end of m.txt, which has 0 renders");
}

TEST(ManifestTest, IndexesAreOneOrARangeAndRendersAreCounted) {
    EXPECT_EQ(*parse_index_range("3"), (IndexRange{3, 3}));
    EXPECT_EQ(*parse_index_range("0-99"), (IndexRange{0, 99}));
    EXPECT_EQ(parse_index_range("5-2").error().message,
              "expected an index I or a range A-B of indexes (A <= B, from 0), got '5-2'");
    EXPECT_FALSE(parse_index_range("-2").ok());
    EXPECT_FALSE(parse_index_range("2-").ok());
    EXPECT_FALSE(parse_index_range("x").ok());
    EXPECT_EQ(count_renders("# renders\n\na.yaml -o a.mp4\n  # later\nb.yaml -o b.png"), 2u);
    EXPECT_EQ(count_renders(""), 0u);
}

std::map<std::string, std::string> environment;
const char* fake_getenv(const char* name) {
    const auto found = environment.find(name);
    return found == environment.end() ? nullptr : found->second.c_str();
}

TEST(ManifestTest, TheIndexComesFromTheFlagThenSlurmThenKubernetes) {
    environment = {{"SLURM_ARRAY_TASK_ID", "4"}, {"JOB_COMPLETION_INDEX", "7"}};
    EXPECT_EQ(*batch_index(IndexRange{2, 5}, fake_getenv), (IndexRange{2, 5}));
    EXPECT_EQ(*batch_index(std::nullopt, fake_getenv), (IndexRange{4, 4}));
    environment = {{"JOB_COMPLETION_INDEX", "7"}};
    EXPECT_EQ(*batch_index(std::nullopt, fake_getenv), (IndexRange{7, 7}));
    environment = {{"SLURM_ARRAY_TASK_ID", "4x"}};
    EXPECT_EQ(batch_index(std::nullopt, fake_getenv).error().message,
              "SLURM_ARRAY_TASK_ID is '4x', not an index (0, 1, 2, ...)");
    environment = {};
    EXPECT_NE(batch_index(std::nullopt, fake_getenv).error().message.find("--index I"),
              std::string::npos);
}

}  // namespace
}  // namespace discreel::app
