"""The case file's JSON Schema (docs/case.schema.json, printed by `sph-cli schema`;
crates/sph-cli/tests/end_to_end/cli.rs checks that the two agree): every example case conforms, an
unknown or misspelt key is flagged as an editor would flag it, and the case-file
reference (docs/case_file.md) is the one scripts/case_reference.py generates from the schema, naming
exactly its keys."""

import json
import re
import sys

import jsonschema
import pytest

from conftest import EXAMPLES, ROOT, tomllib

SCHEMA = json.loads((ROOT / "docs" / "case.schema.json").read_text())


def resolve(node):
    """A subschema with its $ref followed."""
    while "$ref" in node:
        node = SCHEMA["$defs"][node["$ref"].split("/")[-1]]
    return node


def table_of(node):
    """The table a key holds (its schema), if it holds a table or an array of tables."""
    node = resolve(node)
    if node.get("type") == "array":
        node = resolve(node.get("items", {}))
    if "properties" in node or "oneOf" in node:
        return node
    return None


def keys_of(node):
    """The keys of a table schema; the union over the variants of a tagged one."""
    if "oneOf" in node:
        return set().union(*(keys_of(resolve(v)) for v in node["oneOf"]))
    return set(node.get("properties", {}))


def schema_keys():
    """`key` for top-level keys, `table.key` for the keys of tables and arrays of tables,
    and `table.sub.key` for arrays of tables inside a table (`[[diagnostics.sensors]]`)
    and for the keys of a table inside one whose keys are all described, at any depth
    (and of the arrays of tables in it: `wall.free.springs.point`)."""
    found = set()
    for key, node in SCHEMA["properties"].items():
        table = table_of(node)
        if table is None:
            found.add(key)
            continue
        for sub in keys_of(table):
            inner = resolve(table.get("properties", {}).get(sub, {}))
            nested = table_of(inner)
            if inner.get("type") == "array" and nested is not None:
                found.update(f"{key}.{sub}.{k}" for k in keys_of(nested))
                continue
            found.add(f"{key}.{sub}")
            found.update(described_rows(f"{key}.{sub}", nested))
    return found


def described_rows(prefix, table):
    """The rows of a table whose every key is described (`prescribed.pivot`): a row per
    key, the keys of an array of tables in it (`[[wall.free.springs]]`), and the rows of
    a table in it, likewise (`prescribed.waves.spectrum.seed`)."""
    props = (table or {}).get("properties", {})
    if not props or not all(v.get("description") for v in props.values()):
        return set()
    found = set()
    for k, v in props.items():
        inner = resolve(v)
        deeper = table_of(inner)
        if inner.get("type") == "array" and deeper is not None:
            found.update(f"{prefix}.{k}.{d}" for d in keys_of(deeper))
            continue
        found.add(f"{prefix}.{k}")
        if deeper is not None:
            found.update(described_rows(f"{prefix}.{k}", deeper))
    return found


def readme_keys():
    """The keys of the case-file reference (docs/case_file.md): the first cell of each row, e.g.
    `[[tank]] lo, hi, layers` or `[initial] type = "taylor_green", amplitude`."""
    text = (ROOT / "docs" / "case_file.md").read_text()
    section = text.split("## Case-file reference", 1)[1].split("\n## ", 1)[0]
    found = set()
    for row in re.findall(r"^\| `([^|]+?)` \|", section, flags=re.M):
        row = re.sub(r"\{[^}]*\}", "", row.replace("`", ""))  # `reference = { ... }`
        cells = [c.strip() for c in row.split(",")]
        match = re.match(r"\[\[?([\w.]+)\]\]?\s+(.*)", cells[0])
        table, cells[0] = (match.group(1), match.group(2)) if match else (None, cells[0])
        for cell in cells:
            key = re.split(r"\s*=", cell)[0].strip()
            found.add(f"{table}.{key}" if table else key)
    return found


def test_the_readme_reference_is_generated_from_the_schema():
    sys.path.insert(0, str(ROOT / "scripts"))
    import case_reference

    readme = (ROOT / "docs" / "case_file.md").read_text()
    assert case_reference.with_reference(readme) == readme, (
        "the case-file reference (docs/case_file.md) is not current: run python3 scripts/case_reference.py")


def test_the_readme_reference_names_the_schema_keys():
    schema, readme = schema_keys(), readme_keys()
    assert not schema - readme, f"keys missing from docs/case_file.md: {schema - readme}"
    assert not readme - schema, f"docs/case_file.md keys the case file does not have: {readme - schema}"


def test_the_module_ships_the_same_schema():
    import deltasph as ds

    assert json.loads(ds.case_schema()) == SCHEMA


def example_cases():
    return sorted(EXAMPLES.rglob("*.toml"))


@pytest.mark.parametrize("path", example_cases(), ids=lambda p: p.name)
def test_every_example_conforms(path):
    with open(path, "rb") as f:
        jsonschema.validate(tomllib.load(f), SCHEMA)


def test_editors_flag_unknown_keys_and_wrong_values():
    with open(EXAMPLES / "dam_break_2d.toml", "rb") as f:
        case = tomllib.load(f)
    case["scheme"]["difusion"] = "delta_sph"
    with pytest.raises(jsonschema.ValidationError, match="difusion"):
        jsonschema.validate(case, SCHEMA)
    del case["scheme"]["difusion"]
    case["scheme"]["integrator"] = "euler"
    with pytest.raises(jsonschema.ValidationError, match="euler"):
        jsonschema.validate(case, SCHEMA)
    del case["particles"]
    with pytest.raises(jsonschema.ValidationError, match="particles"):
        jsonschema.validate(case, SCHEMA)


def test_editors_flag_the_keys_of_the_other_box():
    """Fluid blocks take no body name, and walls no initial fluid state."""
    with open(EXAMPLES / "dam_break_2d.toml", "rb") as f:
        case = tomllib.load(f)
    block = case["fluid_block"][0]
    jsonschema.validate(case, SCHEMA)
    block["name"] = "water"
    with pytest.raises(jsonschema.ValidationError, match="name"):
        jsonschema.validate(case, SCHEMA)
    del block["name"]
    case["wall"] = [{"lo": [1.0, 0.0], "hi": [1.2, 0.2], "velocity": [1.0, 0.0]}]
    with pytest.raises(jsonschema.ValidationError, match="velocity"):
        jsonschema.validate(case, SCHEMA)
