#!/usr/bin/env python3
"""Make a bundle of strata's binaries that runs on another Linux machine
without Debian's packages, for scripts/gpu-bench.sh --bundle DIR.

    scripts/gpu-bundle.py DIR [--models FILE.csg...]

DIR/bin must hold strata-bench and strata-render (a Release build's, copied).
The script fills:

- DIR/lib: every shared library the two binaries load, copied from this
  machine and stripped, except glibc's own and the GL/EGL/GLX/glvnd
  libraries (the other machine's GL driver and glvnd must be used).
  Libraries that the benchmarks never call are replaced by stubs (below);
- DIR/fonts: Liberation Sans (regular and bold), OpenSCAD's default font,
  and a fonts.conf naming only that folder, for models with text();
- DIR/models: the given scene files, with the files they import (`file =
  "..."` in a .csg), next to them as the .csg expects;
- DIR/MANIFEST: the libraries copied (with their Debian package), stubbed,
  and left to the system.

A stub has the real library's file name (soname) and version nodes, and
defines exactly the symbols the copied objects import from it, so the
dynamic loader is satisfied. Its data are zero-filled, of the real size;
its constructors and destructors return at once; version queries (QUIET)
return 0; every other function prints its name and aborts, so a path that
does need the library stops loudly instead of going wrong.
STRATA_STUB_TRACE=1 in the environment makes them print and return 0
instead, to list what a run calls. The stubbed libraries, and why
strata-bench and strata-render do not need them:

- Embree: only `strata-render --reference` (the CPU ray caster);
- lib3MF: only `--export FILE.3mf`;
- ICU (libicuuc, and with it its 30 MiB of data): only libxml2's conversion
  of SVG files in encodings other than UTF-8, UTF-16 and Latin-1.

So `--reference` and `--export FILE.3mf` stop at a stub with its name;
everything else strata-render and strata-bench do runs as on a full
install, and gives the same images. Take a library off STUBBED to bundle
it (lib3MF adds 2 MiB, ICU 32 MiB).
"""
import argparse
import os
import re
import shutil
import subprocess
import sys

# glibc's own libraries and the GL ones: taken from the machine that runs.
SYSTEM = re.compile(r"^(libc\.so|libm\.so|libpthread\.so|libdl\.so|librt\.so|ld-linux|libresolv\.so"
                    r"|libEGL\.so|libGL\.so|libGLESv2\.so|libOpenGL\.so|libGLX\.so|libGLdispatch\.so"
                    r"|libgbm\.so|libglapi\.so|libvulkan\.so)")
STUBBED = [
    # the reference ray caster; 3MF export; libxml2's encoding conversions
    "libembree3.so.3", "lib3MF.so.1", "libicuuc.so.72",
]
# Stubs that report a version: they return 0 (or an empty string) and say nothing.
QUIET = re.compile(r"[Vv]ersion")
FONTS = ["/usr/share/fonts/truetype/liberation2/LiberationSans-Regular.ttf",
         "/usr/share/fonts/truetype/liberation2/LiberationSans-Bold.ttf"]
FONT_LICENCE = "/usr/share/doc/fonts-liberation2/copyright"


def run(*cmd):
    return subprocess.run(cmd, capture_output=True, text=True, check=True).stdout


def needed(path):
    return re.findall(r"\(NEEDED\).*\[(.*)\]", run("readelf", "-dW", path))


def locations(binaries):
    """soname -> path, as the loader resolves them here."""
    where = {}
    for b in binaries:
        for line in run("ldd", b).splitlines():
            m = re.match(r"\s*(\S+) => (/\S+)", line)
            if m:
                where[m.group(1)] = m.group(2)
    return where


def dynsyms(path):
    """(defined, undefined): defined as {(name, version or None): (type, size, default)},
    undefined as a set of (name, version or None)."""
    defined, undefined = {}, set()
    for line in run("readelf", "--dyn-syms", "-W", path).splitlines():
        f = line.split()
        if len(f) < 8 or not f[0][:-1].isdigit() or f[4] == "LOCAL":
            continue
        typ, size, ndx, name = f[3], f[2], f[6], f[7]
        if name == "":
            continue
        version, default = None, True
        if "@@" in name:
            name, version = name.split("@@", 1)
        elif "@" in name:
            name, version = name.split("@", 1)
            default = ndx == "UND"
        if ndx == "UND":
            undefined.add((name, version))
        else:
            size = int(size, 0) if size.startswith("0x") else int(size)
            defined[(name, version)] = (typ, size, default)
    return defined, undefined


def version_needs(path):
    """{soname: set of version names} this object asks for."""
    needs, current = {}, None
    text = run("readelf", "-V", "-W", path)
    part = text.split("Version needs section", 1)
    if len(part) < 2:
        return needs
    for line in part[1].splitlines():
        m = re.search(r"File: (\S+)", line)
        if m:
            current = m.group(1)
            needs.setdefault(current, set())
            continue
        m = re.search(r"Name: (\S+)", line)
        if m and current:
            needs[current].add(m.group(1))
    return needs


def closure(binaries, where):
    """Copied, stubbed and system libraries reached from the binaries."""
    copied, stubbed, system, todo = [], [], [], []
    for b in binaries:
        todo += needed(b)
    seen = set()
    while todo:
        name = todo.pop(0)
        if name in seen:
            continue
        seen.add(name)
        if name in STUBBED:
            stubbed.append(name)
            continue
        if SYSTEM.match(name):
            system.append(name)
            if name not in where:
                continue  # the dynamic loader itself
        elif name not in where:
            sys.exit(f"gpu-bundle: {name} not found here (ldd)")
        else:
            copied.append(name)
        # the GL libraries' own dependencies (libX11 for libGLX) are copied too
        todo += needed(where[name])
    return copied, stubbed, system


def special_members(names):
    """The names that demangle to a constructor or destructor. Their stubs
    return at once: objects of the stubbed libraries' types that the copied
    libraries define at namespace scope (OpenImageIO's DCMTK registration)
    are built and destroyed at start-up and exit, and used by nothing else."""
    out = subprocess.run(["c++filt"], input="\n".join(names) + "\n", capture_output=True,
                         text=True, check=True).stdout.splitlines()
    found = set()
    for name, pretty in zip(names, out):
        head = pretty.split("(")[0]
        while re.search(r"<[^<>]*>", head):
            head = re.sub(r"<[^<>]*>", "", head)
        parts = head.split("::")
        if len(parts) >= 2 and parts[-1].lstrip("~") == parts[-2]:
            found.add(name)
    return found


def make_stub(soname, real, users, out_dir, work):
    """Write out_dir/soname: the symbols `users` import from `real`."""
    real_defined, _ = dynsyms(real)
    versions = set(users["needs"].get(soname, set()))
    wanted = {}  # (name, version) -> (type, size, default)
    for (name, version) in users["undefined"]:
        if version is None and name in users["defined_elsewhere"]:
            continue
        if version is not None and version not in versions:
            continue  # another library's version
        hit = real_defined.get((name, version))
        if hit is None and version is None:
            hit = next((v for (n, _), v in real_defined.items() if n == name and v[2]), None)
        if hit is not None:
            wanted[(name, version)] = hit
    names = sorted(wanted, key=lambda k: (k[0], k[1] or ""))
    structors = special_members([n for n, _ in names])
    asm = ['.section .note.GNU-stack,"",@progbits', ".section .rodata", "__stub_empty: .quad 0"]
    by_version, seen = {}, set()
    for i, key in enumerate(names):
        name, version = key
        typ, size, _ = wanted[key]
        # unversioned: the name itself; versioned: a local label given the
        # version by .symver (one name may be wanted in two versions)
        label = name if version is None else f"__stub_s{i}"
        size = max(size, 1)
        if typ in ("FUNC", "IFUNC", "NOTYPE") and name in structors:
            asm += [".text", f".globl {label}", f".type {label},@function", f"{label}:", "ret"]
        elif typ in ("FUNC", "IFUNC", "NOTYPE") and QUIET.search(name):
            asm += [".text", f".globl {label}", f".type {label},@function", f"{label}:",
                    "lea __stub_empty(%rip),%rax", "ret"]
        elif typ in ("FUNC", "IFUNC", "NOTYPE"):
            asm += [".section .rodata", f'__stub_n{i}: .asciz "{name}"', ".text",
                    f".globl {label}", f".type {label},@function", f"{label}:",
                    f"lea __stub_n{i}(%rip),%rdi", "jmp __strata_stub_called@PLT"]
        elif typ == "TLS":
            asm += ['.section .tbss,"awT",@nobits', ".balign 16", f".globl {label}",
                    f".type {label},@tls_object", f".size {label},{size}", f"{label}: .zero {size}"]
        else:
            asm += [".bss", ".balign 16", f".globl {label}", f".type {label},@object",
                    f".size {label},{size}", f"{label}: .zero {size}"]
        if version is not None:
            asm.append(f".symver {label}, {name}{'@' if name in seen else '@@'}{version}")
            seen.add(name)
            by_version.setdefault(version, []).append(name)
    for v in sorted(versions):
        by_version.setdefault(v, [])
    src = os.path.join(work, soname + ".s")
    with open(src, "w") as f:
        f.write("\n".join(asm) + "\n")
    trap = os.path.join(work, "trap.c")
    with open(trap, "w") as f:
        f.write('#include <stdio.h>\n#include <stdlib.h>\n'
                '__attribute__((visibility("hidden"))) long __strata_stub_called(const char* name) {\n'
                f'    fprintf(stderr, "%s: a stub of the bundle ({soname}); this library is not bundled\\n", name);\n'
                '    if (!getenv("STRATA_STUB_TRACE")) abort();\n'
                '    return 0;\n}\n')
    cmd = ["gcc", "-shared", "-fPIC", "-o", os.path.join(out_dir, soname), src, trap,
           f"-Wl,-soname,{soname}", "-Wl,--no-undefined"]
    if by_version:
        vs = os.path.join(work, soname + ".map")
        with open(vs, "w") as f:
            for i, v in enumerate(sorted(by_version)):
                f.write(f"{v} {{\n")
                syms = sorted(set(by_version[v]))
                if syms:
                    f.write("  global: " + " ".join(f'"{s}";' for s in syms) + "\n")
                if i == 0:
                    f.write("  local: __stub_*; __strata_stub_called;\n")
                f.write("};\n")
        cmd.append(f"-Wl,--version-script={vs}")
    subprocess.run(cmd, check=True)
    return len(wanted)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("bundle")
    p.add_argument("--models", nargs="*", default=[])
    a = p.parse_args()
    bins = [os.path.join(a.bundle, "bin", b) for b in ("strata-bench", "strata-render")]
    where = locations(bins)
    copied, stubbed, system = closure(bins, where)

    lib = os.path.join(a.bundle, "lib")
    shutil.rmtree(lib, ignore_errors=True)
    os.makedirs(lib)
    for name in copied:
        dst = os.path.join(lib, name)
        shutil.copy2(os.path.realpath(where[name]), dst)
        os.chmod(dst, 0o755)
        subprocess.run(["strip", "--strip-unneeded", dst], check=True)

    # What the loaded objects import, and what they define themselves.
    users = {"undefined": set(), "needs": {}, "defined_elsewhere": set()}
    for obj in bins + [where[n] for n in copied + system if n in where]:
        d, u = dynsyms(obj)
        users["undefined"] |= u
        users["defined_elsewhere"] |= {n for (n, _) in d}
        for soname, vs in version_needs(obj).items():
            users["needs"].setdefault(soname, set()).update(vs)
    work = os.path.join(lib, ".stub-src")
    os.makedirs(work)
    counts = {}
    for name in stubbed:
        counts[name] = make_stub(name, os.path.realpath(where[name]), users, lib, work)
    shutil.rmtree(work)

    fonts = os.path.join(a.bundle, "fonts")
    shutil.rmtree(fonts, ignore_errors=True)
    os.makedirs(fonts)
    for f in FONTS + [FONT_LICENCE]:
        shutil.copy2(f, fonts if f != FONT_LICENCE else os.path.join(fonts, "LICENCE-liberation"))
    with open(os.path.join(fonts, "fonts.conf"), "w") as f:
        f.write('<?xml version="1.0"?>\n<!DOCTYPE fontconfig SYSTEM "fonts.dtd">\n'
                "<!-- Only the bundle's fonts; scripts/gpu-bench.sh points FONTCONFIG_FILE here. -->\n"
                "<fontconfig>\n  <dir prefix=\"relative\">.</dir>\n"
                "  <cachedir>/tmp/strata-fontconfig-cache</cachedir>\n</fontconfig>\n")

    if a.models:
        models = os.path.join(a.bundle, "models")
        shutil.rmtree(models, ignore_errors=True)
        os.makedirs(models)
        for m in a.models:
            shutil.copy2(m, models)
            with open(m, errors="replace") as f:
                for dep in sorted(set(re.findall(r'file = "([^"]+)"', f.read()))):
                    src = os.path.join(os.path.dirname(m), dep)
                    if not os.path.isabs(dep) and os.path.isfile(src):
                        shutil.copy2(src, models)

    with open(os.path.join(a.bundle, "MANIFEST"), "w") as f:
        f.write("# scripts/gpu-bundle.py: libraries of bin/, copied from Debian's packages or stubbed\n")
        for name in sorted(copied):
            pkg = subprocess.run(["dpkg", "-S", where[name], "/usr" + where[name]],
                                 capture_output=True, text=True).stdout.split(":")[0]
            f.write(f"copied {name} {pkg}\n")
        for name in sorted(stubbed):
            f.write(f"stubbed {name} {counts[name]} symbols\n")
        for name in sorted(system):
            f.write(f"system {name}\n")
    total = sum(os.path.getsize(os.path.join(r, x)) for r, _, fs in os.walk(a.bundle) for x in fs)
    print(f"{a.bundle}: {len(copied)} libraries copied, {len(stubbed)} stubbed; "
          f"{total / 1048576:.1f} MiB in all")


if __name__ == "__main__":
    main()
