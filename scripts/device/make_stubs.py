#!/usr/bin/env python3
"""Stand-in shared libraries for OpenImageIO's format plugins that a device run never calls.

usage: make_stubs.py OUT_DIR STUB_LIBS CONSUMERS PROVIDERS
  STUB_LIBS  comma-separated sonames in /lib/x86_64-linux-gnu to stand in for (libopenvdb.so.10.0, ...)
  CONSUMERS  comma-separated sonames that import from them (libOpenImageIO.so.2.4)
  PROVIDERS  comma-separated paths of the libraries that travel for real (and the C/C++ run-time)

Debian's OpenImageIO links every format library it can read (DICOM, FFmpeg, OpenVDB, OpenCV,
HEIF, RAW...): 240 libraries, 357 MB, over the 64 MiB a device call carries. thalassa writes only
EXR and PNG. Each stand-in has the real library's soname and version nodes and defines every
symbol the consumers import from it and nothing kept defines, so that the loader (OpenImageIO is
linked with BIND_NOW) accepts it: functions return the address of 4 KiB of zeros (OpenImageIO's
plugin catalogue asks each library for its version string at start-up, and static constructors
such as DCMTK's DiRegister run at load), objects are zeros of the real size. The stand-ins are
for measuring on a lent machine only (scripts/device/make_kit); nothing installed uses them.
"""
import collections
import os
import re
import subprocess
import sys

LIBDIR = "/lib/x86_64-linux-gnu"


def dynsyms(path):
    """(type, bind, section index, name with version, size) of each dynamic symbol."""
    text = subprocess.run(["readelf", "-W", "--dyn-syms", path], capture_output=True, text=True,
                          check=True).stdout
    for line in text.splitlines():
        m = re.match(r"\s*\d+:\s+[0-9a-f]+\s+(\d+|0x[0-9a-f]+)\s+(\w+)\s+(\w+)\s+\w+\s+(\w+)\s+(\S+)",
                     line)
        if m:
            yield m.group(2), m.group(3), m.group(4), m.group(5), int(m.group(1), 0)


def split(name):
    """'sym@@VER', 'sym@VER' or 'sym' -> (sym, VER or None)."""
    for sep in ("@@", "@"):
        if sep in name:
            return tuple(name.split(sep, 1))
    return name, None


def version_nodes(path):
    """The version definitions of a library, its own soname (the base) first."""
    text = subprocess.run(["readelf", "-W", "-V", path], capture_output=True, text=True,
                          check=True).stdout
    if "Version definition section" not in text:
        return []
    section = text.split("Version definition section")[1].split("Version needs section")[0]
    return re.findall(r"Name: (\S+)", section)


def main():
    out, stubs, consumers, providers = sys.argv[1], *(a.split(",") for a in sys.argv[2:5])
    os.makedirs(out, exist_ok=True)
    wanted = set()
    for consumer in consumers:
        for _, _, index, name, _ in dynsyms(os.path.join(LIBDIR, consumer)):
            if index == "UND":
                wanted.add(split(name)[0])
    # A symbol that a travelling library defines must resolve there, not to a stand-in that
    # comes earlier in the loader's search order.
    provided = set()
    for path in providers:
        for _, _, index, name, _ in dynsyms(path):
            if index != "UND":
                provided.add(split(name)[0])
    for lib in stubs:
        real = os.path.join(LIBDIR, lib)
        versions = version_nodes(real)[1:]
        functions, objects = [], []
        for kind, bind, index, name, size in dynsyms(real):
            symbol, version = split(name)
            if index == "UND" or symbol not in wanted or symbol in provided:
                continue
            if kind in ("FUNC", "IFUNC"):
                functions.append((symbol, version, bind))
            elif kind in ("OBJECT", "NOTYPE"):
                objects.append((symbol, version, bind, max(size, 8)))
            else:
                sys.exit(f"{lib}: {symbol} is a {kind}, which make_stubs.py does not stand in for")
        asm = [".bss", ".balign 64", "stub_zeros:", ".zero 4096", ".text"]
        for symbol, _, bind in functions:
            asm += [f'.{"weak" if bind == "WEAK" else "globl"} "{symbol}"',
                    f'.type "{symbol}",@function', f'"{symbol}":',
                    "leaq stub_zeros(%rip), %rax", "ret"]
        asm.append(".data")
        for symbol, _, bind, size in objects:
            asm += [f'.{"weak" if bind == "WEAK" else "globl"} "{symbol}"',
                    f'.type "{symbol}",@object', f'.size "{symbol}",{size}', ".balign 16",
                    f'"{symbol}":', f".zero {size}"]
        base = os.path.join(out, lib)
        with open(base + ".s", "w") as f:
            f.write("\n".join(asm) + "\n")
        command = ["gcc", "-shared", "-nostdlib", "-o", base, base + ".s", f"-Wl,-soname,{lib}"]
        if versions:
            by_version = collections.defaultdict(list)
            for symbol, version, *_ in functions + objects:
                by_version[version].append(symbol)
            with open(base + ".map", "w") as f:
                for version in versions:
                    names = "".join(f'    "{s}";\n' for s in by_version.get(version, []))
                    f.write(f"{version} {{\n  global:\n{names}}};\n" if names else f"{version} {{ }};\n")
            command.append(f"-Wl,--version-script={base}.map")
        subprocess.run(command, check=True)
        for suffix in (".s", ".map"):
            if os.path.exists(base + suffix):
                os.remove(base + suffix)
        print(f"{lib}: {len(functions)} functions, {len(objects)} objects, {len(versions)} versions")


if __name__ == "__main__":
    main()
