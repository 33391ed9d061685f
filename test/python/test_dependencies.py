#!/usr/bin/env python3
"""The package's declared dependencies against what `make deps` installs.

package.xml declares each dependency by key; rosdep.yaml maps each key to Debian packages; the
Makefile's APT_PACKAGES installs them on a bare machine. On a bare Debian 12 root a missing
entry only shows as a test dying far away (a rostest that cannot import diagnostic_msgs), so
this test checks the three against each other and against dpkg: which Debian package really
owns a ROS package's package.xml, and which one provides each Python module a script imports.

Usage: test_dependencies.py [--junit FILE]   (from the repository or its catkin link folder)
"""
import ast
import os
import pathlib
import subprocess
import sys
import unittest

import junit_main
from make_environment import clean_make_environment
import xml.etree.ElementTree as ElementTree

import yaml

REPOSITORY = pathlib.Path(__file__).resolve().parents[2]
DEPENDENCY_TAGS = ("depend", "build_depend", "build_export_depend", "exec_depend", "test_depend",
                   "buildtool_depend", "buildtool_export_depend", "doc_depend")
# Folders whose Python files run with the package (scripts, rostest checkers, test helpers, the
# Python API).
PYTHON_FOLDERS = ("scripts", "test", "python")
OWN_MODULES = {"acc_identification"}


def declared_keys():
    """{key: [tags]} of every dependency in package.xml."""
    keys = {}
    root = ElementTree.parse(REPOSITORY / "package.xml").getroot()
    for tag in DEPENDENCY_TAGS:
        for element in root.findall(tag):
            keys.setdefault(element.text.strip(), []).append(tag)
    return keys


def rosdep_map():
    with open(REPOSITORY / "rosdep.yaml") as stream:
        entries = yaml.safe_load(stream)
    return {key: list(entry.get("debian") or []) for key, entry in entries.items()}


def apt_packages():
    output = subprocess.run(["make", "-s", "--no-print-directory", "-C", str(REPOSITORY),
                             "print-apt-packages"], check=True, capture_output=True, text=True,
                            env=clean_make_environment())
    return set(output.stdout.split())


def owning_packages(path):
    """The Debian packages that installed path (a folder may have several), empty if none."""
    result = subprocess.run(["dpkg-query", "-S", path], capture_output=True, text=True)
    if result.returncode != 0:
        return set()
    owners = set()
    for line in result.stdout.splitlines():
        # "python3-pil.imagetk:amd64, python3-pil:amd64: /usr/lib/python3/dist-packages/PIL"
        names = line.split(": ", 1)[0]
        owners.update(name.strip().split(":")[0] for name in names.split(","))
    return owners


def installed(package):
    result = subprocess.run(["dpkg-query", "-W", "-f=${Status}", package], capture_output=True,
                            text=True)
    return result.returncode == 0 and "install ok installed" in result.stdout


def python_files():
    for folder in PYTHON_FOLDERS:
        for path in sorted((REPOSITORY / folder).rglob("*.py")):
            yield path


def imported_modules(path):
    """Top-level module names that a Python file imports (absolute imports only)."""
    tree = ast.parse(path.read_text(), filename=str(path))
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for alias in node.names:
                yield alias.name.split(".")[0]
        elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            yield node.module.split(".")[0]


def python_module_packages(module):
    """The Debian packages that provide a Python module; empty when none is installed."""
    # SUMO's TraCI client lives in its tools folder (Debian's sumo-tools), which the replay script
    # puts on its path itself.
    for candidate in (f"/usr/lib/python3/dist-packages/{module}",
                      f"/usr/lib/python3/dist-packages/{module}.py",
                      f"/usr/share/sumo/tools/{module}"):
        if os.path.exists(candidate):
            return owning_packages(candidate)
    return set()


class DeclaredDependencies(unittest.TestCase):
    def setUp(self):
        self.declared = declared_keys()
        self.mapping = rosdep_map()
        self.apt = apt_packages()

    def test_every_declared_key_has_debian_packages(self):
        missing = sorted(key for key in self.declared if not self.mapping.get(key))
        self.assertEqual(missing, [], "package.xml keys without Debian packages in rosdep.yaml")

    def test_every_mapped_package_is_in_the_makefile(self):
        missing = sorted(f"{key} -> {package}" for key in self.declared
                         for package in self.mapping.get(key, []) if package not in self.apt)
        self.assertEqual(missing, [], "Debian packages of package.xml keys missing from the "
                                      "Makefile's APT_PACKAGES")

    def test_no_stale_mapping(self):
        stale = sorted(set(self.mapping) - set(self.declared))
        self.assertEqual(stale, [], "rosdep.yaml keys that package.xml does not declare")

    def test_makefile_packages_are_installed(self):
        # make test ran make deps first: a name that apt could not install would show here.
        missing = sorted(package for package in self.apt if not installed(package))
        self.assertEqual(missing, [], "APT_PACKAGES not installed after make deps")

    def test_ros_keys_map_to_the_package_that_provides_them(self):
        wrong = []
        for key in self.declared:
            owners = owning_packages(f"/usr/share/{key}/package.xml")
            if owners and not owners & set(self.mapping.get(key, [])):
                wrong.append(f"{key} is provided by {sorted(owners)}, rosdep.yaml says "
                             f"{self.mapping.get(key)}")
        self.assertEqual(wrong, [])

    def test_every_imported_python_module_is_declared(self):
        problems = []
        package_to_keys = {}
        for key, packages in self.mapping.items():
            for package in packages:
                package_to_keys.setdefault(package, set()).add(key)
        for path in python_files():
            relative = path.relative_to(REPOSITORY)
            for module in sorted(set(imported_modules(path))):
                # A module beside the script is the package's own (Python puts the script's
                # folder first on its path).
                beside = (path.parent / (module + ".py")).exists()
                if module in sys.stdlib_module_names or module in OWN_MODULES or beside:
                    continue
                packages = python_module_packages(module)
                if not packages:
                    problems.append(f"{relative} imports {module}, which no installed Debian "
                                    "package provides: add its package")
                    continue
                keys = {key for package in packages for key in package_to_keys.get(package, ())}
                if not keys & set(self.declared):
                    problems.append(f"{relative} imports {module} from Debian package(s) "
                                    f"{sorted(packages)}, which no dependency of package.xml "
                                    "maps to")
        self.assertEqual(problems, [])

    def test_the_checks_see_the_files(self):
        # Guards the test itself: an empty scan would pass every check above.
        self.assertGreater(len(self.declared), 10)
        self.assertGreater(len(list(python_files())), 3)
        self.assertIn("diagnostic_msgs", {module for path in python_files()
                                          for module in imported_modules(path)})


def main():
    junit_main.run(DeclaredDependencies)


if __name__ == "__main__":
    main()
