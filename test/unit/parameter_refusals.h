#pragma once

// The refusals of a wrong type that every parameter source must give for the values of
// test/rostest/node_parameters.test (half: 2.5, integer: 7, flag: true, word: along_track,
// quoted_number: "12", mixed_list: [fix, 3]): the parameter server in the rostest, a YAML file in
// test_parameters. One list, so that a tool reading the node's file refuses what the node refuses,
// in the same words.
#include <gtest/gtest.h>

#include <string>
#include <vector>

/// refusal(name, value): the reader's error for one read of ~name into a value of that type.
template <typename Refusal>
void expectEveryWrongTypeRefusedByName(Refusal refusal)
{
  EXPECT_EQ(refusal("half", 3), "parameter ~half is the number 2.5, not an integer");
  EXPECT_EQ(refusal("integer", false), "parameter ~integer is the integer 7, not true or false");
  EXPECT_EQ(refusal("integer", std::string("x")), "parameter ~integer is the integer 7, not a string");
  EXPECT_EQ(refusal("flag", 1.0), "parameter ~flag is the bool true, not a number");
  // Quoted on purpose in the YAML: a string, without the exponent's hint.
  EXPECT_EQ(refusal("word", 1.0), "parameter ~word is the string \"along_track\", not a number");
  EXPECT_NE(refusal("quoted_number", 1.0).find("the string \"12\", not a number"), std::string::npos);
  EXPECT_EQ(refusal("mixed_list", std::vector<std::string>{"a"}),
            "parameter ~mixed_list is a list of 2 values, not a list of strings");
  EXPECT_EQ(refusal("word", std::vector<std::string>{"a"}),
            "parameter ~word is the string \"along_track\", not a list of strings");
}
