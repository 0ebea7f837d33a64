"""The functions an ELF shared library exports, read from its file without loading it.

A deck names a C library and a function in it; checking at load that the function exists must
not run the library's code (loading it with dlopen runs its initialisers), so the dynamic symbol
table is read directly: the ELF header, the section headers, the ``SHT_DYNSYM`` section and its
string table (System V ABI, "Object Files"). Libraries that are not ELF (macOS's Mach-O) are
left to the loader at compile time.
"""
import struct

_SHT_DYNSYM = 11
_STT_FUNC, _STT_GNU_IFUNC = 2, 10
_STB_GLOBAL, _STB_WEAK = 1, 2


class NotElf(ValueError):
    """The file is not an ELF object, or its tables are truncated."""


def exported_functions(path):
    """The names of the functions `path` defines and exports (global or weak).

    Raises
    ------
    NotElf
        The file is not a well-formed ELF object.
    OSError
        The file cannot be read.
    """
    with open(path, "rb") as fh:
        data = fh.read()
    if data[:4] != b"\x7fELF" or len(data) < 64 or data[4] not in (1, 2) or data[5] not in (1, 2):
        raise NotElf("not an ELF file")
    wide, end = data[4] == 2, "<" if data[5] == 1 else ">"
    try:
        if wide:
            shoff, = struct.unpack_from(end + "Q", data, 0x28)
            shentsize, shnum = struct.unpack_from(end + "HH", data, 0x3A)
            sec_fmt, sym_fmt, sym_size = end + "IIQQQQIIQQ", end + "IBBHQQ", 24
        else:
            shoff, = struct.unpack_from(end + "I", data, 0x20)
            shentsize, shnum = struct.unpack_from(end + "HH", data, 0x2E)
            sec_fmt, sym_fmt, sym_size = end + "IIIIIIIIII", end + "IIIBBH", 16
        sections = [struct.unpack_from(sec_fmt, data, shoff + i * shentsize)
                    for i in range(shnum)]
        names = set()
        for sec in sections:
            if sec[1] != _SHT_DYNSYM:
                continue
            offset, size, link = sec[4], sec[5], sec[6]
            strtab = sections[link]
            strings = data[strtab[4]:strtab[4] + strtab[5]]
            for pos in range(offset, offset + size, sym_size):
                sym = struct.unpack_from(sym_fmt, data, pos)
                if wide:
                    name, info, shndx = sym[0], sym[1], sym[3]
                else:
                    name, info, shndx = sym[0], sym[3], sym[5]
                if shndx == 0 or info & 0xF not in (_STT_FUNC, _STT_GNU_IFUNC) \
                        or info >> 4 not in (_STB_GLOBAL, _STB_WEAK):
                    continue
                names.add(strings[name:strings.index(b"\0", name)].decode(errors="replace"))
        return names
    except (struct.error, IndexError, ValueError) as err:
        raise NotElf(f"truncated or malformed ELF tables ({err})") from None
