"""The one main of the package's Python test files: `FILE.py --junit OUT.xml` writes a JUnit report
(catkin's test results), anything else runs unittest as usual."""
import os
import sys
import unittest


def run(test_case, arguments=None):
    """Runs test_case (a unittest.TestCase class) with the command line's arguments; exits."""
    arguments = sys.argv[1:] if arguments is None else arguments
    if len(arguments) == 2 and arguments[0] == "--junit":
        from rosunit import xmlrunner
        # The results folder may not exist yet when this is the first test catkin runs.
        os.makedirs(os.path.dirname(os.path.abspath(arguments[1])), exist_ok=True)
        with open(arguments[1], "w") as report:
            runner = xmlrunner.XMLTestRunner(stream=report)
            result = runner.run(unittest.defaultTestLoader.loadTestsFromTestCase(test_case))
        sys.exit(0 if result.wasSuccessful() else 1)
    unittest.main(argv=[sys.argv[0]] + arguments, verbosity=2)
