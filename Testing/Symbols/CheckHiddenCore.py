#!/usr/bin/env python3
"""The module library must define no Core (namespace accelvolume) symbol in its dynamic symbol
table: CheckHiddenCore.py <library>.

Core is a static library linked into the module with hidden visibility. When the module exported
Core's functions (default visibility, -fPIC), calls between them went through the PLT, and GCC
12's -O1 -fsanitize=thread build of that layout built a wrong cell-leap table (the TSan "NaN
voxels" failure, docs/sanitizers.md). A program that links both the module and Core (the tests,
the CLI, the benchmarks) must also get its own copy, never the module's.
"""
import re
import subprocess
import sys


def main():
    library = sys.argv[1]
    listing = subprocess.run(["nm", "-D", "-C", "--defined-only", library], check=True,
                             capture_output=True, text=True).stdout
    exported = [line for line in listing.splitlines()
                if re.match(r"^[0-9a-f]+ [A-Za-z] (typeinfo (name )?for |vtable for )?accelvolume::",
                            line)]
    if exported:
        print("%s exports %d Core symbols, e.g.:\n  %s" % (
            library, len(exported), "\n  ".join(exported[:10])))
        return 1
    print("%s: no Core symbol exported" % library)
    return 0


if __name__ == "__main__":
    sys.exit(main())
