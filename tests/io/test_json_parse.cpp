// parse_json: values come back as nlohmann reads them; nesting past kMaxJsonDepth is refused at
// the bracket that goes too deep, at any depth up to a million; a number out of range and a
// syntax error are placed by the key path they were met under, and by line and column.
#include "io/json_parse.hpp"

#include <gtest/gtest.h>

#include <string>

#include "io/json_reader.hpp"
#include "support/temp_file.hpp"

namespace vdc {
namespace {

std::string nested_arrays(int depth) { return std::string(static_cast<std::size_t>(depth), '[') + std::string(static_cast<std::size_t>(depth), ']'); }

TEST(JsonParse, ValuesComeBackAsTheLibraryReadsThem) {
  const std::string text = R"({"a": [1, 2.5, "x", null, true, {"b": []}], "c": {"d": -3, "e": 18446744073709551615}})";
  const JsonParse parsed = parse_json(text);
  ASSERT_EQ(parsed.problem, "");
  EXPECT_EQ(parsed.value, nlohmann::json::parse(text));
  EXPECT_EQ(parsed.value.dump(), nlohmann::json::parse(text).dump());
  EXPECT_EQ(parse_json("7").value, nlohmann::json(7));
}

TEST(JsonParse, NestingUpToTheBoundIsReadAndOneDeeperIsRefusedAtItsBracket) {
  const JsonParse deepest = parse_json(nested_arrays(kMaxJsonDepth));
  EXPECT_EQ(deepest.problem, "");
  const JsonParse over = parse_json(nested_arrays(kMaxJsonDepth + 1));
  EXPECT_EQ(over.problem, "arrays and objects nested deeper than " + std::to_string(kMaxJsonDepth));
  // The bracket that opens level kMaxJsonDepth + 1 is character kMaxJsonDepth + 1 of line 1.
  EXPECT_EQ(over.at, "line 1, column " + std::to_string(kMaxJsonDepth + 1));
  EXPECT_EQ(over.value, nlohmann::json(nullptr));
}

TEST(JsonParse, AMillionLevelsUnderAKeyAreRefusedNamingTheKey) {
  const int depth = 1000000;
  std::string text = "{\"camera\": {\"keys\": ";
  text += nested_arrays(depth);
  text += "}}";
  const JsonParse parsed = parse_json(text);
  EXPECT_EQ(parsed.problem, "arrays and objects nested deeper than " + std::to_string(kMaxJsonDepth));
  // camera and keys are two levels; the arrays under keys go 98 deep before the refused one.
  std::string path = "camera.keys";
  for (int level = 3; level <= kMaxJsonDepth; ++level) path += "[0]";
  EXPECT_EQ(parsed.place, shortened(path, 120));
  EXPECT_EQ(parsed.at, "line 1, column " + std::to_string(20 + kMaxJsonDepth - 1));
  // Strings are not nesting: brackets inside them are skipped when the bracket is placed.
  const JsonParse quoted = parse_json("{\"a\": \"[[[[\\\"[[\", \"b\": " + nested_arrays(depth) + "}");
  EXPECT_EQ(quoted.at, "line 1, column " + std::to_string(23 + kMaxJsonDepth));
}

TEST(JsonParse, ObjectsNestedPastTheBoundAreRefusedToo) {
  std::string text;
  for (int i = 0; i < 500000; ++i) text += "{\"a\":";
  text += "1";
  text += std::string(500000, '}');
  EXPECT_EQ(parse_json(text).problem, "arrays and objects nested deeper than " + std::to_string(kMaxJsonDepth));
}

TEST(JsonParse, ANumberOutOfRangeNamesItsKeyPathLineAndColumn) {
  const JsonParse top = parse_json("{\"frame_time\": 1e400}");
  EXPECT_EQ(top.problem, "number out of range: 1e400");
  EXPECT_EQ(top.place, "frame_time");
  EXPECT_EQ(top.at, "line 1, column 16");
  EXPECT_EQ(json_failure_place(top), "frame_time (line 1, column 16)");

  const JsonParse deep = parse_json("{\"garments\": [{}, {\"transform\": {\"translate\": [0,\n 0, -1e999]}}]}");
  EXPECT_EQ(deep.problem, "number out of range: -1e999");
  EXPECT_EQ(deep.place, "garments[1].transform.translate[2]");
  EXPECT_EQ(deep.at, "line 2, column 5");

  const JsonParse alone = parse_json("1e400");
  EXPECT_EQ(alone.place, "");
  EXPECT_EQ(json_failure_place(alone), "line 1, column 1");
}

TEST(JsonParse, ASyntaxErrorKeepsTheLibrarysWordsAndGainsItsKeyPath) {
  const JsonParse parsed = parse_json("{\"solver\": {\"tolerance\": 1e-3,}}");
  EXPECT_EQ(parsed.at, "line 1, column 31");  // the brace where a key should be
  EXPECT_EQ(parsed.place, "solver");
  EXPECT_NE(parsed.problem.find("JSON syntax error: syntax error while parsing object key"), std::string::npos) << parsed.problem;
}

TEST(JsonParse, TheStrictReaderNamesTheFileKeyAndPlace) {
  test::TempFile file(".json");
  file.write("{\"name\": \"x\",\n \"solver\": {\"tolerance\": 1e400}}");
  try {
    JsonValue::load_file(file.path());
    ADD_FAILURE() << "read without complaint";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), file.path() + ":solver.tolerance (line 2, column 26): number out of range: 1e400");
  }
}

TEST(JsonParse, AFileForReadersThatCanDoWithoutItIsNullWhenItCannotBeRead) {
  test::TempFile file(".json");
  file.write(nested_arrays(200000));
  EXPECT_TRUE(read_json_or_null(file.path()).is_null());
  file.write("{\"status\": \"done\"}");
  EXPECT_EQ(read_json_or_null(file.path()), nlohmann::json({{"status", "done"}}));
  EXPECT_TRUE(read_json_or_null(file.path() + ".missing").is_null());
}

}  // namespace
}  // namespace vdc
