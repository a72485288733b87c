#!/usr/bin/python3
"""The documented JSON Schema (docs/schema) accepts what simtree writes and rejects broken trees.

usage: check_tree_schema.py <simtree> <schema.json> <shared data dir> <tmp dir>
"""
import json
import pathlib
import subprocess
import sys

import jsonschema

simtree, schema_path, data, tmp = sys.argv[1:5]
tmp = pathlib.Path(tmp)
tmp.mkdir(parents=True, exist_ok=True)
schema = json.load(open(schema_path))
jsonschema.Draft202012Validator.check_schema(schema)
validator = jsonschema.Draft202012Validator(schema)

demo = pathlib.Path(data) / "authors-demo"
out = tmp / "tree01.json"
subprocess.run([simtree, "-q", "convert", str(demo / "tree_model/tree01.txt"), str(out),
                "--params", str(demo / "tree_parameters.txt")], check=True)
doc = json.load(open(out))
errors = list(validator.iter_errors(doc))
assert not errors, f"simtree's own output fails the schema: {errors[0].message}"

def broken(edit):
    d = json.loads(json.dumps(doc))
    edit(d)
    return any(True for _ in validator.iter_errors(d))

assert broken(lambda d: d.update(version=2))
assert broken(lambda d: d["branches"][1]["nodes"].__setitem__(0, [0, 0, 0]))
assert broken(lambda d: d["branches"][1]["material"]["modes"][0].update(kind="twist_v"))
assert broken(lambda d: d["branches"][1]["material"].update(source="guessed"))
assert broken(lambda d: d["branches"][1].pop("parent"))
print("schema ok: simtree output validates; 5 broken variants rejected")
