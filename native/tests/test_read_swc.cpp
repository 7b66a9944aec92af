#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <string>
#include <string_view>
#include <vector>

#include "test_support.hpp"
#include "vesselmesh/error.hpp"
#include "vesselmesh/read/read.hpp"

namespace vesselmesh {
namespace {

const std::string kSource = "fixture.swc";

/// The message of the InputError that parsing `text` throws; a test failure when it does not throw.
std::string error_of(std::string_view text) {
  try {
    parse_swc(text, kSource);
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "parse_swc accepted:\n" << text;
  return "";
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// Three points in a chain 1 <- 2 <- 3, reused by the format-variant tests.
constexpr const char* kChain =
    "1 1 0 0 0 1.0 -1\n"
    "2 3 1 0 0 0.5 1\n"
    "3 3 2 0 0 0.25 2\n";

void expect_chain(const CenterlineData& data) {
  ASSERT_EQ(data.points.size(), 3u);
  EXPECT_EQ(data.points[2], Vec3(2, 0, 0));
  EXPECT_EQ(data.radius, (std::vector<double>{1.0, 0.5, 0.25}));
  EXPECT_EQ(data.edges, (std::vector<Edge>{{0, 1}, {1, 2}}));
  EXPECT_EQ(data.roots, (std::vector<int32_t>{0}));
  EXPECT_TRUE(data.edge_radius.empty());
}

TEST(ReadSwc, ReadsPointsRadiiParentEdgesAndRootInFileOrder) {
  const CenterlineData data = parse_swc(
      "1 1 10.5 -2 3e1 2.5 -1\n"
      "2 3 11 -2.5 30 1.5 1\n"
      "3 3 12 -3 31 1.25 2\n"
      "4 3 11 -1 32 1 2\n",
      kSource);
  ASSERT_EQ(data.points.size(), 4u);
  EXPECT_EQ(data.points[0], Vec3(10.5, -2, 30));
  EXPECT_EQ(data.points[3], Vec3(11, -1, 32));
  EXPECT_EQ(data.radius, (std::vector<double>{2.5, 1.5, 1.25, 1}));
  EXPECT_EQ(data.edges, (std::vector<Edge>{{0, 1}, {1, 2}, {1, 3}}));
  EXPECT_EQ(data.roots, (std::vector<int32_t>{0}));
  EXPECT_NO_THROW(validate(data, kSource));
}

TEST(ReadSwc, SkipsCommentsIndentedCommentsAndBlankLines) {
  expect_chain(parse_swc(std::string("# header\n   # indented comment\n\n") + "1 1 0 0 0 1.0 -1\n\t\n" +
                             "\t# tab-indented comment\n2 3 1 0 0 0.5 1\n   \n3 3 2 0 0 0.25 2\n# trailing\n",
                         kSource));
}

TEST(ReadSwc, AcceptsCrlfLineEndingsAndAByteOrderMark) {
  expect_chain(parse_swc(
      "\xEF\xBB\xBF# made on Windows\r\n1 1 0 0 0 1.0 -1\r\n2 3 1 0 0 0.5 1\r\n3 3 2 0 0 0.25 2\r\n",
      kSource));
}

TEST(ReadSwc, AcceptsTabsAndRunsOfSpacesAroundColumns) {
  expect_chain(
      parse_swc("  1\t1\t0\t0\t0\t1.0\t-1\n"
                "2    3  1 \t 0   0 0.5     1   \n"
                "\t\t3 3 2 0 0 0.25 2\t\n",
                kSource));
}

TEST(ReadSwc, IgnoresColumnsAfterTheSeventh) {
  expect_chain(
      parse_swc("1 1 0 0 0 1.0 -1 extra 7\n"
                "2 3 1 0 0 0.5 1 # note\n"
                "3 3 2 0 0 0.25 2 0.0 anything\n",
                kSource));
}

TEST(ReadSwc, LastLineWithoutNewlineIsRead) {
  expect_chain(parse_swc("1 1 0 0 0 1.0 -1\n2 3 1 0 0 0.5 1\n3 3 2 0 0 0.25 2", kSource));
}

TEST(ReadSwc, AcceptsAnyIntegerTypeValue) {
  expect_chain(
      parse_swc("1 0 0 0 0 1.0 -1\n"
                "2 -7 1 0 0 0.5 1\n"
                "3 123456 2 0 0 0.25 2\n",
                kSource));
}

TEST(ReadSwc, AcceptsIntegerColumnsWrittenWithAZeroFraction) {
  expect_chain(
      parse_swc("1.0 1.0 0 0 0 1.0 -1.0\n"
                "2.0 3.0 1 0 0 0.5 1.0\n"
                "3.0 3.0 2 0 0 0.25 2.0\n",
                kSource));
}

TEST(ReadSwc, AcceptsUnsortedNonSequentialIdsWithParentsAfterChildren) {
  const CenterlineData data = parse_swc(
      "30 3 2 0 0 0.25 200\n"
      "200 3 1 0 0 0.5 7\n"
      "7 1 0 0 0 1.0 -1\n",
      kSource);
  ASSERT_EQ(data.points.size(), 3u);
  EXPECT_EQ(data.points[0], Vec3(2, 0, 0));
  EXPECT_EQ(data.radius, (std::vector<double>{0.25, 0.5, 1.0}));
  EXPECT_EQ(data.edges, (std::vector<Edge>{{1, 0}, {2, 1}}));
  EXPECT_EQ(data.roots, (std::vector<int32_t>{2}));
}

TEST(ReadSwc, RecordsTheRootOfEveryComponent) {
  const CenterlineData data = parse_swc(
      "1 1 0 0 0 1 -1\n"
      "2 3 1 0 0 1 1\n"
      "10 1 5 0 0 1 -1\n"
      "11 3 6 0 0 1 10\n"
      "12 3 7 0 0 1 11\n"
      "20 1 9 9 9 1 -1\n",
      kSource);
  EXPECT_EQ(data.roots, (std::vector<int32_t>{0, 2, 5}));
  EXPECT_EQ(data.edges, (std::vector<Edge>{{0, 1}, {2, 3}, {3, 4}}));
}

TEST(ReadSwc, TreatsAnyNegativeParentAsARoot) {
  const CenterlineData data = parse_swc(
      "1 1 0 0 0 1 -1\n"
      "2 3 1 0 0 1 1\n"
      "3 1 5 0 0 1 -2\n"
      "4 3 6 0 0 1 3\n"
      "5 1 8 0 0 1 -999\n",
      kSource);
  EXPECT_EQ(data.roots, (std::vector<int32_t>{0, 2, 4}));
  EXPECT_EQ(data.edges, (std::vector<Edge>{{0, 1}, {2, 3}}));
}

TEST(ReadSwc, AcceptsNegativeAndZeroIds) {
  const CenterlineData data = parse_swc(
      "0 1 0 0 0 1 -1\n"
      "-3 3 1 0 0 1 0\n",
      kSource);
  EXPECT_EQ(data.edges, (std::vector<Edge>{{0, 1}}));
}

TEST(ReadSwc, ReadsAMillionLinesIncludingAChainListedLeafFirst) {
  // Leaf first: every parent lies further down, so a quadratic walk or a recursive one would show here.
  constexpr int kN = 1000000;
  std::string text;
  text.reserve(kN * 24);
  for (int id = 1; id <= kN; ++id)
    text += std::to_string(id) + " 3 " + std::to_string(id % 1000) + " 0 0 1.5 " +
            (id == kN ? std::string("-1") : std::to_string(id + 1)) + "\n";
  const CenterlineData data = parse_swc(text, kSource);
  EXPECT_EQ(data.points.size(), static_cast<std::size_t>(kN));
  EXPECT_EQ(data.edges.size(), static_cast<std::size_t>(kN - 1));
  EXPECT_EQ(data.roots, (std::vector<int32_t>{kN - 1}));
  EXPECT_EQ(data.edges.front(), (Edge{1, 0}));
}

// --- errors: each names the file and the line ---

TEST(ReadSwc, LineWithFewerThanSevenColumnsIsRejectedWithTheCount) {
  const std::string message = error_of("1 1 0 0 0 1 -1\n2 3 1 0 0 1\n");
  EXPECT_TRUE(
      contains(message, "fixture.swc: line 2: expected 7 columns: id type x y z radius parent, found 6"))
      << message;
}

TEST(ReadSwc, ColumnCountErrorCountsCommentAndBlankLines) {
  const std::string message = error_of("# comment\n\n1 1 0 0 0 1 -1\r\n2 3 1\r\n");
  EXPECT_TRUE(contains(message, "fixture.swc: line 4: expected 7 columns")) << message;
  EXPECT_TRUE(contains(message, "found 3")) << message;
}

TEST(ReadSwc, LineNumbersAreCountedAfterAByteOrderMark) {
  const std::string message = error_of(std::string("\xEF\xBB\xBF") + "1 1 0 0 0 1 -1\nbad\n");
  EXPECT_TRUE(contains(message, "fixture.swc: line 2: expected 7 columns")) << message;
}

TEST(ReadSwc, NonNumericCoordinateIsRejectedNamingTheLine) {
  const std::string message = error_of("1 1 0 0 0 1 -1\n2 3 1 abc 0 1 1\n");
  EXPECT_TRUE(contains(message, "fixture.swc: line 2: expected a number for y, found 'abc'")) << message;
}

TEST(ReadSwc, NonNumericRadiusIsRejectedNamingTheLine) {
  const std::string message = error_of("1 1 0 0 0 1 -1\n2 3 1 0 0 1,5 1\n");
  EXPECT_TRUE(contains(message, "fixture.swc: line 2: expected a number for the radius, found '1,5'"))
      << message;
}

TEST(ReadSwc, FractionalIdIsRejectedNamingTheLine) {
  const std::string message = error_of("1 1 0 0 0 1 -1\n2.5 3 1 0 0 1 1\n");
  EXPECT_TRUE(contains(message, "fixture.swc: line 2: expected an integer for the id, found '2.5'"))
      << message;
}

TEST(ReadSwc, NonIntegerTypeIsRejectedNamingTheLine) {
  const std::string message = error_of("1 soma 0 0 0 1 -1\n");
  EXPECT_TRUE(contains(message, "fixture.swc: line 1: expected an integer for the type, found 'soma'"))
      << message;
}

TEST(ReadSwc, NonIntegerParentIsRejectedNamingTheLine) {
  const std::string message = error_of("1 1 0 0 0 1 -1\n2 3 1 0 0 1 one\n");
  EXPECT_TRUE(contains(message, "fixture.swc: line 2: expected an integer for the parent id, found 'one'"))
      << message;
}

TEST(ReadSwc, NanAndInfinityAreRejectedNamingTheLine) {
  for (const char* bad : {"nan", "NaN", "inf", "-inf", "infinity", "1e999"}) {
    const std::string message = error_of("1 1 0 0 0 1 -1\n2 3 " + std::string(bad) + " 0 0 1 1\n");
    EXPECT_TRUE(contains(message, "fixture.swc: line 2: expected a number for x") ||
                contains(message, "fixture.swc: line 2: x is not a finite number"))
        << bad << ": " << message;
  }
  const std::string message = error_of("1 1 0 0 0 nan -1\n");
  EXPECT_TRUE(contains(message, "fixture.swc: line 1: the radius is not a finite number")) << message;
}

TEST(ReadSwc, IdOutOfTheIntegerRangeIsRejectedNamingTheLine) {
  const std::string message = error_of("99999999999999999999 1 0 0 0 1 -1\n");
  EXPECT_TRUE(contains(message, "fixture.swc: line 1: expected an integer for the id")) << message;
}

TEST(ReadSwc, DuplicateIdIsRejectedNamingBothLines) {
  const std::string message = error_of(
      "1 1 0 0 0 1 -1\n"
      "2 3 1 0 0 1 1\n"
      "# comment\n"
      "2 3 2 0 0 1 1\n");
  EXPECT_TRUE(contains(message, "fixture.swc: line 4: duplicate id 2 (first on line 2)")) << message;
}

TEST(ReadSwc, MissingParentIsRejectedNamingTheChildLine) {
  const std::string message = error_of(
      "1 1 0 0 0 1 -1\n"
      "2 3 1 0 0 1 1\n"
      "3 3 2 0 0 1 42\n"
      "4 3 3 0 0 1 3\n");
  EXPECT_TRUE(contains(message, "fixture.swc: line 3: parent id 42 of node 3 does not exist")) << message;
}

TEST(ReadSwc, NodeThatIsItsOwnParentIsRejectedNamingItsLine) {
  const std::string message = error_of(
      "1 1 0 0 0 1 -1\n"
      "2 3 1 0 0 1 1\n"
      "5 3 2 0 0 1 5\n");
  EXPECT_TRUE(contains(message, "fixture.swc: line 3: node 5 is its own parent")) << message;
}

TEST(ReadSwc, ParentCycleIsRejectedNamingALineInTheCycle) {
  // Node 9 (line 2) hangs off the cycle 3 -> 4 -> 5 -> 3 on lines 4 to 6: it never reaches a root
  // either, but the line named must be one of the cycle's.
  const std::string message = error_of(
      "1 1 0 0 0 1 -1\n"
      "9 3 1 0 0 1 4\n"
      "2 3 2 0 0 1 1\n"
      "3 3 3 0 0 1 4\n"
      "4 3 4 0 0 1 5\n"
      "5 3 5 0 0 1 3\n");
  EXPECT_TRUE(contains(message, "parent cycle")) << message;
  EXPECT_TRUE(contains(message, "fixture.swc: line 4: ")) << message;
  EXPECT_TRUE(contains(message, "3 -> 4 -> 5 -> 3")) << message;
}

TEST(ReadSwc, FileThatIsOnlyACycleIsRejected) {
  const std::string message = error_of("1 1 0 0 0 1 2\n2 3 1 0 0 1 1\n");
  EXPECT_TRUE(contains(message, "fixture.swc: line 1: parent cycle")) << message;
}

TEST(ReadSwc, LongParentCycleIsRejectedWithAShortenedChain) {
  std::string text = "1 1 0 0 0 1 -1\n";
  for (int id = 100; id < 150; ++id)
    text += std::to_string(id) + " 3 0 0 0 1 " + std::to_string(id + 1) + "\n";
  text += "150 3 0 0 0 1 100\n";
  const std::string message = error_of(text);
  EXPECT_TRUE(contains(message, "fixture.swc: line 2: parent cycle")) << message;
  EXPECT_TRUE(contains(message, " -> ...")) << message;
  EXPECT_LT(message.size(), 200u) << message;
}

TEST(ReadSwc, ZeroRadiusIsRejectedNamingTheLine) {
  const std::string message = error_of("1 1 0 0 0 1 -1\n2 3 1 0 0 0 1\n");
  EXPECT_TRUE(contains(message, "fixture.swc: line 2: radius must be positive, found 0")) << message;
}

TEST(ReadSwc, NegativeRadiusIsRejectedNamingTheLine) {
  const std::string message = error_of("1 1 0 0 0 1 -1\n2 3 1 0 0 1 1\n3 3 1 0 0 -0.5 2\n");
  EXPECT_TRUE(contains(message, "fixture.swc: line 3: radius must be positive, found -0.5")) << message;
}

TEST(ReadSwc, EmptyFileIsRejectedAsHavingNoPoints) {
  EXPECT_TRUE(contains(error_of(""), "fixture.swc: no points")) << error_of("");
  EXPECT_TRUE(contains(error_of("\xEF\xBB\xBF"), "fixture.swc: no points"));
  EXPECT_TRUE(contains(error_of("\n\r\n  \t\n"), "fixture.swc: no points"));
}

TEST(ReadSwc, CommentOnlyFileIsRejectedAsHavingNoPoints) {
  const std::string message = error_of("# id type x y z radius parent\n# nothing else\n");
  EXPECT_TRUE(contains(message, "fixture.swc: no points")) << message;
}

TEST(ReadSwc, TruncatedLastLineIsRejectedNamingIt) {
  const std::string message = error_of("1 1 0 0 0 1 -1\n2 3 1 0 0 1 1\n3 3 2 0");
  EXPECT_TRUE(contains(message, "fixture.swc: line 3: expected 7 columns")) << message;
}

TEST(ReadSwc, BinaryBytesAreRejectedWithAnInputErrorNamingALine) {
  std::mt19937 random(12345);
  std::uniform_int_distribution<int> byte(0, 255);
  for (int trial = 0; trial < 50; ++trial) {
    std::string bytes(1 + trial * 97, '\0');
    for (char& c : bytes) c = static_cast<char>(byte(random));
    bytes[0] = '\x01';  // not a comment
    const std::string message = error_of(bytes);
    EXPECT_TRUE(contains(message, "fixture.swc: line ")) << message;
  }
}

TEST(ReadSwc, NumbersFollowedByBinaryBytesAreRejected) {
  const std::string message = error_of(std::string("1 1 0 0 0 1 -1\n2 3 1 0 0") + '\0' + "\x7f 1 1\n");
  EXPECT_TRUE(contains(message, "fixture.swc: line 2: expected a number for z")) << message;
}

// --- the shared real data sets, read through read_centerline (dispatch by extension, validation) ---

void expect_radius_range(const CenterlineData& data, double lo, double hi) {
  ASSERT_FALSE(data.radius.empty());
  const auto [min, max] = std::minmax_element(data.radius.begin(), data.radius.end());
  EXPECT_NEAR(*min, lo, 1e-9);
  EXPECT_NEAR(*max, hi, 1e-9);
}

TEST(ReadSwcSharedData, BravaColorCodedCngTreeHasOneRootAndItsRadiusRange) {
  SHARED_DATA_OR_SKIP(path, "brava-bg0003/BG0003_ColorCoded.CNG.swc");
  const CenterlineData data = read_centerline(path);
  EXPECT_EQ(data.points.size(), 3470u);
  EXPECT_EQ(data.edges.size(), 3469u);
  EXPECT_EQ(data.roots.size(), 1u);
  expect_radius_range(data, 0.31, 3.1);
}

TEST(ReadSwcSharedData, BravaRecordsWithMixedTabsAndSpacesReadAsOneTree) {
  SHARED_DATA_OR_SKIP(path, "brava-bg0003/records.swc");
  const CenterlineData data = read_centerline(path);
  EXPECT_EQ(data.points.size(), 3470u);
  EXPECT_EQ(data.edges.size(), 3469u);
}

TEST(ReadSwcSharedData, HemibrainNeuronWithCommentHeaderReadsAsOneTree) {
  SHARED_DATA_OR_SKIP(path, "neuron-hemibrain-da1/1734350788.swc");
  const CenterlineData data = read_centerline(path);
  EXPECT_EQ(data.points.size(), 4465u);
  EXPECT_EQ(data.edges.size(), 4464u);
}

}  // namespace
}  // namespace vesselmesh
