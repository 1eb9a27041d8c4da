#!/usr/bin/env python3
"""Checks docs/scene.schema.json against the scenes that use it.

  - the schema itself is a valid JSON Schema (draft 2020-12);
  - every *.json of the --scenes folders (scenes/, tests/data/scenes/) validates against it;
  - every file in the --bad folder is rejected by it (so the schema is not
    vacuous: it catches misspelt keys, wrong types, bad enums, ...).

Exit status: 0 when all hold, 1 otherwise, 77 (CTest "skipped") when the
python3-jsonschema package is not installed.
"""

import argparse
import glob
import json
import os
import sys

try:
    import jsonschema
except ImportError:
    print("python3-jsonschema is not installed; skipping", file=sys.stderr)
    sys.exit(77)


def load(path):
    with open(path, encoding="utf-8") as f:
        return json.load(f)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--schema", required=True)
    parser.add_argument("--scenes", required=True, nargs="+", help="folders whose *.json must validate")
    parser.add_argument("--bad", required=True, help="folder whose *.json must NOT validate")
    args = parser.parse_args()

    schema = load(args.schema)
    validator_class = jsonschema.validators.validator_for(schema)
    validator_class.check_schema(schema)
    validator = validator_class(schema)
    failures = 0

    scenes = []
    for folder in args.scenes:
        found = sorted(glob.glob(os.path.join(folder, "*.json")))
        if not found:
            print("no scenes found in %s" % folder)
            failures += 1
        scenes += found
    for path in scenes:
        errors = sorted(validator.iter_errors(load(path)), key=lambda e: list(e.absolute_path))
        for e in errors:
            where = "/".join(str(p) for p in e.absolute_path) or "(top level)"
            print("FAIL %s: %s: %s" % (path, where, e.message))
        failures += bool(errors)
        if not errors:
            print("ok   %s" % path)

    bad = sorted(glob.glob(os.path.join(args.bad, "*.json")))
    if len(bad) < 5:
        print("expected at least 5 files in %s, found %d" % (args.bad, len(bad)))
        failures += 1
    for path in bad:
        errors = list(validator.iter_errors(load(path)))
        if errors:
            print("ok   %s is rejected: %s" % (path, errors[0].message))
        else:
            print("FAIL %s is accepted by the schema, but it is not a valid scene" % path)
            failures += 1

    print("%d problem(s)" % failures)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
