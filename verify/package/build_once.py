"""build_once.py SOURCE_DIR WORK_DIR: the Python package's build compiles each object once.

setup.py configures a clean tree and builds it in one parallel call. Under the Makefile generator,
two top-level targets named in one call each recurse into the targets they depend on, so the
shared library both link is compiled by two `make` processes at once in one tree (they delete each
other's dependency files: "opening dependency file ... .o.d: No such file"). Whether that race
strikes depends on timing; what causes it does not: here the build's own command (setup.py's
configure_command and build_command) runs on a clean Makefile tree as a dry run (`make -n -k`, which
still descends into the recursive makes and prints every compiler call without running it), and
every object file must be named as an output exactly once. Seconds: it configures, compiles nothing.
"""

import collections
import os
import re
import runpy
import shutil
import subprocess
import sys
from pathlib import Path

source, work = Path(sys.argv[1]), Path(sys.argv[2])
shutil.rmtree(work, ignore_errors=True)
setup = runpy.run_path(str(source / "setup.py"), run_name="setup_commands")
# A make above this one (ctest run by make) must not pass its jobserver or flags down.
environment = {key: value for key, value in os.environ.items()
               if key not in ("MAKEFLAGS", "MFLAGS", "MAKELEVEL", "CMAKE_BUILD_PARALLEL_LEVEL")}
subprocess.run(setup["configure_command"](work) + ["-G", "Unix Makefiles"], check=True,
               env=environment, stdout=subprocess.DEVNULL)
# -k: a dry run stops where a link needs a library it did not make; the compiler calls of the
# targets beyond are wanted too (the exit status of a dry run says nothing).
dry_run = subprocess.run(setup["build_command"](work, 4) + ["--", "-n", "-k"],
                         env=environment, capture_output=True, text=True).stdout
outputs = collections.Counter(re.findall(r"\s-o\s+(\S+\.o)\b", dry_run))
library = [name for name in outputs if "CMakeFiles/gearimpact.dir/" in name]
twice = sorted(name for name, count in outputs.items() if count > 1)
print(f"{len(outputs)} objects in the dry run, {len(library)} of the library; "
      f"compiled more than once: {len(twice)}")
for name in twice:
    print(f"  {name}: {outputs[name]} times")
# The dry run must show the library's objects at all (else the check above is empty): the library
# has dozens of sources, the module and the program one and a few.
if len(library) < 10 or twice:
    sys.exit(1)
shutil.rmtree(work, ignore_errors=True)
