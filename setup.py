"""Builds the Python package gearimpact with the project's CMake (see pyproject.toml).

The extension gearimpact._core, the program gearimpact/bin/gearimpact and the
paper's data gearimpact/share/gearimpact/paper_data come from CMake's
`python` install component; the Python files from python/gearimpact.
Environment: CMAKE_BUILD_PARALLEL_LEVEL (jobs, default: the cores),
GEARIMPACT_CMAKE_ARGS (more configure arguments, space separated) and
GEARIMPACT_BUILD_DIR (the CMake build tree, relative to the source tree; default: a folder
in setuptools' build_temp). A compiler cache such as ccache finds the objects of an earlier
build of the same sources only where the build tree sits at the same place relative to them.
"""

import os
import re
import shlex
import subprocess
import sys
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = Path(__file__).resolve().parent


def project_version():
    """The version in CMakeLists.txt's project(), the one home of the version."""
    text = (ROOT / "CMakeLists.txt").read_text()
    match = re.search(r"project\(gearimpact\s+VERSION\s+([0-9.]+)", text)
    if match is None:
        raise RuntimeError("no project(gearimpact VERSION x.y.z) in CMakeLists.txt")
    return match.group(1)


def configure_command(build_dir):
    """The configuration of the package's build tree (without GEARIMPACT_CMAKE_ARGS)."""
    return [
        "cmake",
        "-S", str(ROOT),
        "-B", str(build_dir),
        "-DCMAKE_BUILD_TYPE=Release",
        "-DGEARIMPACT_PYTHON=ON",
        "-DGEARIMPACT_BUILD_TESTS=OFF",
        "-DGEARIMPACT_BUILD_BENCHMARKS=OFF",
        f"-DPython3_EXECUTABLE={sys.executable}",
    ]


def build_command(build_dir, jobs):
    """The build of everything the `python` install component installs: one target that depends
    on the module and the program. Two targets named in one parallel call of the Makefile
    generator would each build the shared library they link, at the same time, in one tree
    (verify/package/build_once.py checks that each object is compiled once)."""
    return ["cmake", "--build", str(build_dir), "-j", str(jobs),
            "--target", "gearimpact_python_package"]


class CMakeExtension(Extension):
    def __init__(self, name):
        super().__init__(name, sources=[])


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        package_parent = Path(self.get_ext_fullpath(ext.name)).resolve().parent.parent
        build_subdir = os.environ.get("GEARIMPACT_BUILD_DIR")
        build_dir = (ROOT / build_subdir if build_subdir
                     else Path(self.build_temp).resolve() / "cmake")
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL", str(os.cpu_count() or 1))
        configure = configure_command(build_dir) + [
            "-DGEARIMPACT_PYTHON_INSTALL_DIR=.",
        ] + shlex.split(os.environ.get("GEARIMPACT_CMAKE_ARGS", ""))
        subprocess.run(configure, check=True)
        subprocess.run(build_command(build_dir, jobs), check=True)
        subprocess.run(
            ["cmake", "--install", str(build_dir), "--component", "python",
             "--prefix", str(package_parent)],
            check=True,
        )


# Run by pip (setuptools' build backend runs this file as __main__) or by hand; imported by
# verify/package/build_once.py for build_command alone.
if __name__ == "__main__":
    setup(
        version=project_version(),
        packages=["gearimpact"],
        package_dir={"gearimpact": "python/gearimpact"},
        ext_modules=[CMakeExtension("gearimpact._core")],
        cmdclass={"build_ext": CMakeBuild},
        zip_safe=False,
    )
