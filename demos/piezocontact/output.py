"""Run outputs, the layout of the C++ solver (cpp/output.h). Every file is
complete whenever a step has been reported, whatever instant a kill lands:
  DIR/summary.json             the run's record (write-then-rename each step)
  DIR/solution.xdmf            index for ParaView (write-then-rename each step)
  DIR/solution.h5              the mesh, written once
  DIR/solution/step_NNNNNN.h5  u, phi (vertex), D, stress (cell) of one step:
                               a new file per step, never reopened, so a
                               write cut short cannot damage earlier steps
  DIR/nodal/{u,phi}_NNNN.npy   nodal values [x, y, value...] on rank 0
  DIR/checkpoint/state_NNNNNN.npy  what --resume needs (checkpoint.py)
Files of steps after the last one in summary.json (a kill came before the
summary) are dropped by --resume, which writes them again.
"""

import ctypes
import errno
import io as _io
import json
import math
import os
import re
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
from dolfinx import fem, io

EXIT_OUTPUT_ERROR = 4
_XI = "http://www.w3.org/2001/XInclude"
_MESH_POINTER = ("xpointer(/Xdmf/Domain/Grid[@GridType='Uniform'][1]/*[self::Topology or "
                 "self::Geometry])")
ET.register_namespace("xi", _XI)


class OutputError(RuntimeError):
    """An output file could not be written; the message names the file and
    the system's reason."""


def _finite(obj):
    """NaN/inf become null, as the C++ writer does: summary.json stays JSON."""
    if isinstance(obj, float):
        return obj if math.isfinite(obj) else None
    if isinstance(obj, dict):
        return {k: _finite(v) for k, v in obj.items()}
    if isinstance(obj, list):
        return [_finite(v) for v in obj]
    return obj


def _reason(directory, err=None, fallback="write failed"):
    """A full disk is named as such (HDF5's own message says only "can't
    write data"); otherwise the system's reason, else `fallback`."""
    try:
        s = os.statvfs(directory)
        full = s.f_bavail * s.f_frsize < 1 << 16
    except OSError:
        full = False
    if full or (err is not None and err.errno == errno.ENOSPC):
        return os.strerror(errno.ENOSPC)
    if err is not None and err.strerror:
        return err.strerror
    return fallback


def write_file_atomic(path, data):
    """Write-then-rename: an interrupted run never leaves a half-written file."""
    path = Path(path)
    tmp = path.with_name("." + path.name + ".tmp")
    try:
        with open(tmp, "wb") as f:
            f.write(data)
        os.replace(tmp, path)
    except OSError as err:
        remove_quietly(tmp)
        raise OutputError(f"cannot write {path}: {_reason(path.parent, err)}") from None


def write_json_atomic(path, obj):
    write_file_atomic(path, (json.dumps(_finite(obj), indent=1, allow_nan=False)
                             + "\n").encode())


def save_npy(path, array):
    """np.save, written atomically."""
    buf = _io.BytesIO()
    np.save(buf, np.ascontiguousarray(array, dtype=np.float64))
    write_file_atomic(path, buf.getvalue())


def collectively(comm, on_this_rank, action):
    """Run `action` on the ranks given; if it failed on any rank, raise the
    same OutputError everywhere (the lowest failing rank's message)."""
    error = None
    if on_this_rank:
        try:
            action()
        except (OSError, RuntimeError) as err:
            error = str(err)
    errors = comm.allgather(error)
    first = next((e for e in errors if e is not None), None)
    if first is not None:
        raise OutputError(first)


def silence_hdf5_errors():
    """Turn HDF5's error-stack printing off: write failures become one line.
    The library is the one dolfinx loaded (found in this process's maps)."""
    with open("/proc/self/maps") as maps:
        libs = {line.split()[-1] for line in maps if re.search(r"/libhdf5[^/]*\.so", line)}
    for lib in libs:
        if "_hl" not in Path(lib).name:
            ctypes.CDLL(lib).H5Eset_auto2(ctypes.c_int64(0), None, None)


def remove_quietly(path):
    try:
        os.remove(path)
    except OSError:
        pass


def _remove_numbered_after(directory, prefix, suffix, last):
    """Files DIR/prefix<digits>suffix numbered above `last`."""
    directory = Path(directory)
    if not directory.is_dir():
        return
    pattern = re.compile(re.escape(prefix) + r"(\d+)" + re.escape(suffix) + "$")
    for p in directory.iterdir():
        m = pattern.match(p.name)
        if m and int(m.group(1)) > last:
            remove_quietly(p)


def gather_nodal(function, comm):
    """[x, y, values...] of the owned dofs of a collapsed P1 function, on rank 0."""
    V = function.function_space
    n = V.dofmap.index_map.size_local
    bs = V.dofmap.index_map_bs
    rows = np.column_stack([V.tabulate_dof_coordinates()[:n, :2],
                            function.x.array[:n * bs].reshape(n, bs)])
    parts = comm.gather(rows, root=0)
    return np.vstack(parts) if comm.rank == 0 else None


def _prefix_data_paths(node, prefix):
    """Data paths of a dolfinx XDMF file are relative to it; the index sits
    one directory up."""
    for item in node.iter("DataItem"):
        if item.get("Format") == "HDF":
            item.text = prefix + item.text.strip()


class Writer:
    def __init__(self, problem, out_dir, cfg, resume_step=0):
        """A fresh run (resume_step = 0) clears earlier outputs of DIR; a
        resumed one keeps steps 1..resume_step and drops anything after."""
        self.problem = problem
        self.comm = problem.comm
        self.dir = Path(out_dir)
        self.nodal = cfg["output"]["nodal"]
        self.xdmf = cfg["output"]["xdmf"]
        root = self.comm.rank == 0
        collectively(self.comm, root, lambda: self._clear(resume_step))
        if not self.xdmf:
            return
        dg0 = ("DG", 0)
        self.D = fem.Function(fem.VectorFunctionSpace(problem.mesh, dg0), name="D")
        self.stress = fem.Function(fem.VectorFunctionSpace(problem.mesh, dg0, dim=3),
                                   name="stress_voigt")
        self.index = None  # rank 0: the ElementTree of solution.xdmf
        index = self.dir / "solution.xdmf"
        if resume_step > 0:
            collectively(self.comm, root, lambda: self._load_index(resume_step))
            return
        # The mesh goes in through dolfinx once, as solution.xdmf/.h5 (so that
        # XDMFFile.read_mesh still reads it there); that XML becomes the index
        self._write_hdf5(index, lambda f: f.write_mesh(problem.mesh))
        collectively(self.comm, root, lambda: self._read_index(index))

    def _clear(self, resume_step):
        d = self.dir
        if resume_step == 0:
            # nothing of an earlier run in DIR may pass for this one's
            for p in (d / "solution.xdmf", d / "solution.h5"):
                remove_quietly(p)
            _remove_numbered_after(d / "solution", "step_", ".h5", -1)
        _remove_numbered_after(d / "solution", "step_", ".h5", resume_step)
        _remove_numbered_after(d / "solution", "step_", ".xdmf", -1)
        # every checkpoint but the one resumed (a kill may
        # land between a summary and the removal of its predecessor's)
        if (d / "checkpoint").is_dir():
            for p in (d / "checkpoint").glob("state_*.npy"):
                if p.name != f"state_{resume_step:06d}.npy" or resume_step == 0:
                    remove_quietly(p)
        for name in ("u_", "phi_"):
            _remove_numbered_after(d / "nodal", name, ".npy", resume_step)
        (d / "nodal").mkdir(parents=True, exist_ok=True)
        (d / "solution").mkdir(parents=True, exist_ok=True)

    def _read_index(self, path):
        try:
            self.index = ET.parse(path)
        except (OSError, ET.ParseError):
            raise OutputError(f"cannot write {path}: "
                              f"{_reason(path.parent, None, 'unreadable after writing')}")

    def _load_index(self, last_step):
        path = self.dir / "solution.xdmf"
        try:
            self.index = ET.parse(path)
        except (OSError, ET.ParseError):
            raise OutputError(f"cannot resume: {path} is missing or unreadable") from None
        # Steps written after the checkpoint are dropped: the resumed run rewrites them
        for series in self._series(self.index.getroot()):
            for grid in series.findall("Grid")[last_step:]:
                series.remove(grid)
        self._publish_index()

    @staticmethod
    def _series(root):
        return [g for g in root.find("Domain").findall("Grid")
                if g.get("GridType") == "Collection"]

    def _write_hdf5(self, xdmf, write):
        """Write one HDF5 file through dolfinx (XML beside it); on failure on
        any rank, remove it and raise OutputError everywhere."""
        error, err = None, None
        try:
            with io.XDMFFile(self.comm, str(xdmf), "w") as f:
                write(f)
        except (RuntimeError, OSError) as e:
            error, err = str(e), e if isinstance(e, OSError) else None
        if not any(self.comm.allgather(error is not None)):
            return
        h5 = Path(xdmf).with_suffix(".h5")
        reason = _reason(h5.parent, err, error or "HDF5 write failed")  # before freeing space
        if self.comm.rank == 0:
            try:  # free the space (the file may still be open), then remove
                os.truncate(h5, 0)
            except OSError:
                pass
            remove_quietly(h5)
            remove_quietly(xdmf)
        raise OutputError(f"cannot write {h5}: {reason}")

    def _merge_step(self, step_xdmf):
        try:
            doc = ET.parse(step_xdmf)
        except (OSError, ET.ParseError):
            raise OutputError(f"cannot write {step_xdmf}: "
                              f"{_reason(step_xdmf.parent, None, 'unreadable after writing')}")
        domain = self.index.getroot().find("Domain")
        for src in self._series(doc.getroot()):
            name = src.get("Name")
            series = next((g for g in self._series(self.index.getroot())
                           if g.get("Name") == name), None)
            if series is None:
                series = ET.SubElement(domain, "Grid", {"Name": name, "GridType": "Collection",
                                                        "CollectionType": "Temporal"})
            for grid in src.findall("Grid"):
                grid.find(f"{{{_XI}}}include").set("xpointer", _MESH_POINTER)
                _prefix_data_paths(grid, "solution/")
                series.append(grid)
        os.remove(step_xdmf)
        self._publish_index()

    def _publish_index(self):
        ET.indent(self.index, space="  ")
        buf = _io.BytesIO()
        self.index.write(buf, xml_declaration=True, encoding="utf-8")
        write_file_atomic(self.dir / "solution.xdmf", buf.getvalue())

    def write_step(self, step, t, final):
        """Write the state of problem.u, problem.phi (updated by the caller)."""
        u, phi = self.problem.u, self.problem.phi
        if self.xdmf:
            self.D.interpolate(self.problem.D_expr)
            self.stress.interpolate(self.problem.stress_expr)
            step_xdmf = self.dir / "solution" / f"step_{step:06d}.xdmf"
            # A new HDF5 file per step, never reopened: an append cut short by
            # a kill could damage a shared file's metadata, and earlier steps
            self._write_hdf5(step_xdmf, lambda f: [f.write_function(fn, t, "/Xdmf/Domain")
                                                   for fn in (u, phi, self.D, self.stress)])
            collectively(self.comm, self.comm.rank == 0, lambda: self._merge_step(step_xdmf))
        if self.nodal == "all" or (self.nodal == "final" and final):
            for name, f in (("u", u), ("phi", phi)):
                rows = gather_nodal(f, self.comm)
                collectively(self.comm, self.comm.rank == 0,
                             lambda: save_npy(self.dir / "nodal" / f"{name}_{step:04d}.npy",
                                              rows))

    def close(self):
        """Nothing is held open between steps."""
