#include <gtest/gtest.h>

// One main for every unit-test binary: catkin's gtest macro links GoogleTest but not its main.
int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
