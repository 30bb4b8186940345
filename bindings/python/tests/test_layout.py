"""The ctypes declarations agree with include/bezjoin.h.

* Every struct of the header that has fields has a ctypes ``Structure`` (class
  ``<Name>Struct`` for ``Bzj<Name>``) with the same field names in the same order,
  and every field has the C compiler's offset and size (a C program generated
  from the ``_fields_`` prints ``offsetof``/``sizeof``), and the field types map
  to the header's.
* Every function of the header has a prototype (argument and result types) that
  maps to the header's declaration.
* Every function of the header is called by the C++ wrapper include/bezjoin.hpp.

So a layout or signature change in the header cannot slip past the bindings.
"""

import ctypes
import importlib
import inspect
import os
import pkgutil
import re
import shutil
import subprocess

import pytest

import bezjoin
from bezjoin import _library

REPOSITORY = os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(
    os.path.abspath(__file__)))))
INCLUDE = os.path.join(REPOSITORY, "include")
HEADER = os.path.join(INCLUDE, "bezjoin.h")
CPP_HEADER = os.path.join(INCLUDE, "bezjoin.hpp")


def header_text():
    with open(HEADER, encoding="utf-8") as file:
        return file.read()


def without_comments(text):
    text = re.sub(r"/\*.*?\*/", "", text, flags=re.S)
    return re.sub(r"//[^\n]*", "", text)


def header_structs():
    """``{name: [(field type, field name), ...]}`` of every ``typedef struct`` with a body."""
    text = without_comments(header_text())
    structs = {}
    for match in re.finditer(r"typedef struct (Bzj\w+) \{(.*?)\} (\w+);", text, flags=re.S):
        name, body, alias = match.groups()
        assert alias == name, f"typedef struct {name} {{...}} {alias}"
        fields = []
        for declaration in body.split(";"):
            declaration = " ".join(declaration.split())
            if not declaration:
                continue
            field = re.fullmatch(r"(.+?)\s*\b(\w+)", declaration)
            assert field, f"{name}: cannot parse field {declaration!r}"
            fields.append((field.group(1).strip(), field.group(2)))
        structs[name] = fields
    return structs


def header_enums():
    return set(re.findall(r"^enum (Bzj\w+)", header_text(), flags=re.M))


def header_functions():
    """``{name: (result type, [argument types])}`` of every function declared."""
    text = without_comments(header_text())
    functions = {}
    for match in re.finditer(r"^([A-Za-z_][\w\s\*]*?)\s*\b(bzj_\w+)\((.*?)\);", text,
                             flags=re.M | re.S):
        result, name, arguments = match.groups()
        types = []
        for argument in arguments.split(","):
            argument = " ".join(argument.split())
            if argument == "void":
                continue
            parameter = re.fullmatch(r"(.+?)\s*\b(\w+)", argument)
            assert parameter, f"{name}: cannot parse argument {argument!r}"
            types.append(parameter.group(1).strip())
        functions[name] = (" ".join(result.split()), types)
    return functions


def ctypes_structs():
    """``{C name: class}`` of every ``ctypes.Structure`` with ``_fields_`` in the package."""
    found = {}
    for module_info in pkgutil.iter_modules(bezjoin.__path__):
        module = importlib.import_module(f"bezjoin.{module_info.name}")
        for _, cls in inspect.getmembers(module, inspect.isclass):
            if (issubclass(cls, ctypes.Structure) and cls.__module__ == module.__name__
                    and "_fields_" in cls.__dict__):
                assert cls.__name__.endswith("Struct"), (
                    f"{module.__name__}.{cls.__name__}: a C struct's class is named "
                    "<Name>Struct for Bzj<Name>")
                found["Bzj" + cls.__name__[:-len("Struct")]] = cls
    return found


def expected_ctypes(c_type, structs, enums):
    """The ctypes type a C type of the header maps to (``None`` for void)."""
    c_type = " ".join(c_type.replace("*", " * ").split())
    scalars = {
        "void": None,
        "double": ctypes.c_double,
        "size_t": ctypes.c_size_t,
        "bool": ctypes.c_bool,
        "int32_t": ctypes.c_int32,
        "uint32_t": ctypes.c_uint32,
        "const char *": ctypes.c_char_p,
    }
    if c_type in scalars:
        return scalars[c_type]
    if c_type in enums:  # int32_t-sized enums (the header's typedef outside C++/C23)
        return ctypes.c_int32
    if c_type.startswith("struct ") and not c_type.endswith("*"):  # a struct field by value
        return structs[c_type[len("struct "):]]
    if c_type.endswith(" *"):
        pointee = c_type[:-2].strip()
        for prefix in ("const ", "struct "):
            if pointee.startswith(prefix):
                pointee = pointee[len(prefix):]
        if pointee.endswith(" * const"):  # const struct BzjCurve *const *
            pointee = pointee[:-len(" const")]
        if pointee == "BzjCurve":
            return _library.CurvePointer
        if pointee == "BzjCurve *":
            return ctypes.POINTER(_library.CurvePointer)
        if pointee.startswith("Bzj"):
            return ctypes.POINTER(structs[pointee])
        return ctypes.POINTER(expected_ctypes(pointee, structs, enums))
    raise AssertionError(f"no ctypes mapping for the C type {c_type!r}")


def test_header_is_parsed():
    # A parser that finds nothing would let every comparison below pass.
    structs = header_structs()
    assert len(structs) >= 13 and "BzjMergeOptions" in structs
    assert [name for _type, name in structs["BzjKeepPoint"]] == ["param", "max_order"]
    assert len(header_functions()) >= 28
    assert header_functions()["bzj_curve_free"] == ("void", ["struct BzjCurve *"])


def test_every_header_struct_has_a_ctypes_structure_and_no_other():
    assert sorted(ctypes_structs()) == sorted(header_structs())


def test_field_names_and_types_match_the_header_in_order():
    structs = ctypes_structs()
    enums = header_enums()
    for name, fields in header_structs().items():
        cls = structs[name]
        assert [field for field, _type in cls._fields_] == [field for _type, field in fields], name
        for (field, ctype), (c_type, _field) in zip(cls._fields_, fields):
            assert ctype is expected_ctypes(c_type, structs, enums), (
                f"{name}.{field}: ctypes {ctype.__name__}, header {c_type!r}")


def compiler():
    for name in ("cc", "gcc", "clang"):
        path = shutil.which(name)
        if path:
            return path
    pytest.fail("no C compiler (cc, gcc, clang) on PATH: the layout cannot be checked")
    return None


def test_offsets_and_sizes_match_the_c_compiler(tmp_path):
    structs = ctypes_structs()
    lines = ['#include <stdalign.h>', '#include <stddef.h>', '#include <stdio.h>',
             '#include "bezjoin.h"', "int main(void) {"]
    for name, cls in sorted(structs.items()):
        lines.append(f'    printf("{name} - %zu %zu\\n", sizeof({name}), alignof({name}));')
        for field, _ctype in cls._fields_:
            lines.append(f'    printf("{name} {field} %zu %zu\\n", offsetof({name}, {field}), '
                         f"sizeof((({name} *)0)->{field}));")
    lines += ["    return 0;", "}"]
    source = tmp_path / "layout.c"
    source.write_text("\n".join(lines) + "\n")
    program = tmp_path / "layout"
    build = subprocess.run([compiler(), "-std=c11", "-Wall", "-Werror", "-I", INCLUDE,
                            str(source), "-o", str(program)],
                           capture_output=True, text=True, check=False)
    assert build.returncode == 0, f"{build.stderr}\n{source.read_text()}"
    run = subprocess.run([str(program)], capture_output=True, text=True, check=True)
    measured = {}
    for line in run.stdout.splitlines():
        name, field, first, second = line.split()
        measured[(name, field)] = (int(first), int(second))
    checked = 0
    for name, cls in structs.items():
        assert measured[(name, "-")] == (ctypes.sizeof(cls), ctypes.alignment(cls)), (
            f"{name}: C (sizeof, alignof) {measured[(name, '-')]}, ctypes "
            f"{(ctypes.sizeof(cls), ctypes.alignment(cls))}")
        for field, _ctype in cls._fields_:
            descriptor = getattr(cls, field)
            assert measured[(name, field)] == (descriptor.offset, descriptor.size), (
                f"{name}.{field}: C (offset, size) {measured[(name, field)]}, ctypes "
                f"{(descriptor.offset, descriptor.size)}")
            checked += 1
    assert checked == sum(len(fields) for fields in header_structs().values())


def test_every_header_function_has_a_matching_prototype():
    structs = ctypes_structs()
    enums = header_enums()
    prototypes = _library._PROTOTYPES
    functions = header_functions()
    assert sorted(set(functions) - set(prototypes)) == [], "header functions without bindings"
    assert sorted(set(prototypes) - set(functions)) == [], "bindings of functions not in the header"
    for name, (result, arguments) in functions.items():
        restype, argtypes = prototypes[name]
        assert restype is expected_ctypes(result, structs, enums), f"{name} result"
        assert len(argtypes) == len(arguments), f"{name}: {len(argtypes)} arguments declared"
        for i, (declared, c_type) in enumerate(zip(argtypes, arguments)):
            assert declared is expected_ctypes(c_type, structs, enums), (
                f"{name} argument {i}: ctypes {declared}, header {c_type!r}")


def test_every_declared_function_is_called_by_the_package():
    package = os.path.dirname(bezjoin.__file__)
    source = ""
    for file_name in sorted(os.listdir(package)):
        if file_name.endswith(".py"):
            with open(os.path.join(package, file_name), encoding="utf-8") as file:
                source += file.read()
    calls = set(re.findall(r'(?:call|function)\(\s*"(bzj_\w+)"', source))
    # bzj_version, bzj_last_error and bzj_status_name are called through
    # Library.function in _library.py; the rest through Library.call.
    assert sorted(set(header_functions()) - calls) == []


def test_every_header_function_is_wrapped_in_cpp():
    with open(CPP_HEADER, encoding="utf-8") as file:
        text = without_comments(file.read())
    called = set(re.findall(r"\b(bzj_\w+)\(", text))
    assert sorted(set(header_functions()) - called) == []
    assert "BEZJOIN_HAS_" not in text
