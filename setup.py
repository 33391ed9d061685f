# The package's Python module (python/acc_identification: the API over the C++ tools) for
# catkin_python_setup(); the compiled part (_core, pybind11) is built by cmake/python.cmake.
from setuptools import setup
from catkin_pkg.python_setup import generate_distutils_setup

setup(**generate_distutils_setup(packages=["acc_identification"], package_dir={"": "python"}))
