"""px4 stand-in: writes OUT/DIALECT/DIALECT.h and OUT/DIALECT/mavlink.h, as PX4's MAVLink
generation step leaves them in the build tree (contents are placeholders)."""
import os
import sys

out_dir, dialect = sys.argv[1], sys.argv[2]
dialect_dir = os.path.join(out_dir, dialect)
os.makedirs(dialect_dir, exist_ok=True)
for name in (dialect + ".h", "mavlink.h"):
    with open(os.path.join(dialect_dir, name), "w", encoding="ascii") as f:
        f.write("#pragma once\n/* px4 stand-in: generated at build time */\n")
