"""STEP files of named solids (AP214, mm): one product per part, or one assembly of them.

Written through OpenCascade's XCAF document and STEP writer (``STEPCAFControl``): each
solid is a product named after its part; an assembly product holds them as placed,
named components. build123d's ``export_step`` would do the naming too but writes no
header description; here the header carries the file's name, ``rotorkin`` as the
originating system and a title (the config's) as ``FILE_DESCRIPTION``, encoded for the
character set of ISO 10303-21. :func:`read_step` reads the names, the placed solids and
the header back (the tests use other readers as well). Re-exported by
:mod:`rotorkin.render.workshop`.
"""

from __future__ import annotations

from pathlib import Path

from rotorkin.core.errors import RotorkinError

__all__ = ["write_step", "read_step"]

_MM = 1e-3


def _location(placement):
    from OCP.gp import gp_Ax1, gp_Dir, gp_Pnt, gp_Trsf, gp_Vec
    from OCP.TopLoc import TopLoc_Location

    x, y, angle, z = (float(v) for v in placement)
    rot, move = gp_Trsf(), gp_Trsf()
    rot.SetRotation(gp_Ax1(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1)), angle)
    move.SetTranslation(gp_Vec(x / _MM, y / _MM, z / _MM))
    return TopLoc_Location(move.Multiplied(rot))


def _quiet() -> None:
    """OpenCascade's messages to the console: failures only (as build123d sets them)."""
    from OCP.Message import Message, Message_Gravity

    for printer in Message.DefaultMessenger_s().Printers():
        printer.SetTraceLevel(Message_Gravity.Message_Fail)


def _p21(text: str) -> str:
    """``text`` in the character set of a STEP file (ISO 10303-21): printable ASCII as it is
    (OpenCascade doubles a backslash and a quote itself), each run of other characters as
    ``\\X2\\hhhh...\\X0\\`` (UCS-2), or ``\\X4\\hhhhhhhh...\\X0\\`` beyond the BMP."""
    import re

    def run(m):
        s = m.group(0)
        if all(ord(c) <= 0xFFFF for c in s):
            return "\\X2\\" + "".join(f"{ord(c):04X}" for c in s) + "\\X0\\"
        return "\\X4\\" + "".join(f"{ord(c):08X}" for c in s) + "\\X0\\"

    return re.sub(r"[^ -~]+", run, str(text))


def _from_p21(text: str) -> str:
    """Inverse of :func:`_p21` on a string read from a file (doubled backslashes undone)."""
    import re

    token = re.compile(r"\\\\|\\X([24])\\([0-9A-F]*)\\X0\\|.", re.S)
    out = []
    for m in token.finditer(text):
        if m.group(0) == "\\\\":
            out.append("\\")
        elif m.group(1):
            w, h = (4 if m.group(1) == "2" else 8), m.group(2)
            out.append("".join(chr(int(h[i : i + w], 16)) for i in range(0, len(h), w)))
        else:
            out.append(m.group(0))
    return "".join(out)


def _unlocated(shape):
    """The shape with its location baked into its geometry: XCAF files a located shape as an
    instance of an unnamed product, which would lose the part's name."""
    from OCP.BRepBuilderAPI import BRepBuilderAPI_Transform
    from OCP.TopLoc import TopLoc_Location

    if shape.Location().IsIdentity():
        return shape
    base = shape.Located(TopLoc_Location())
    return BRepBuilderAPI_Transform(base, shape.Location().Transformation(), True).Shape()


def write_step(path, solids, name: str, title: str = "", assembly: bool = True) -> Path:
    """Write named solids [mm] to a STEP file (AP214), one product per solid.

    Parameters
    ----------
    path : path-like
    solids : sequence of (str, shape, placement)
        Product name (e.g. ``"impeller_2"``), a build123d shape or OCP ``TopoDS_Shape``
        in mm, and its placement ``(x, y, angle, z)`` [m, rad] (rotation about z, then
        the shift), e.g. the part's place in its machine.
    name : str
        The assembly's product name and the header's ``FILE_NAME``.
    title : str
        Written as the header's ``FILE_DESCRIPTION`` (e.g. the config's title).
    assembly : bool
        True: one assembly product ``name`` holding every solid as a placed component;
        False (one solid only): the solid itself as the file's one product, unplaced.

    Returns
    -------
    Path
    """
    from OCP.APIHeaderSection import APIHeaderSection_MakeHeader
    from OCP.IFSelect import IFSelect_ReturnStatus
    from OCP.Interface import Interface_Static
    from OCP.STEPCAFControl import STEPCAFControl_Writer
    from OCP.STEPControl import STEPControl_Controller, STEPControl_StepModelType
    from OCP.TCollection import TCollection_ExtendedString, TCollection_HAsciiString
    from OCP.TDataStd import TDataStd_Name
    from OCP.TDocStd import TDocStd_Document
    from OCP.XCAFApp import XCAFApp_Application
    from OCP.XCAFDoc import XCAFDoc_DocumentTool

    if not assembly and len(solids) != 1:
        raise ValueError("a STEP file without assembly holds one solid")
    doc = TDocStd_Document(TCollection_ExtendedString("XmlOcaf"))
    app = XCAFApp_Application.GetApplication_s()
    app.NewDocument(TCollection_ExtendedString("MDTV-XCAF"), doc)
    XCAFDoc_DocumentTool.SetLengthUnit_s(doc, 0.001)
    tool = XCAFDoc_DocumentTool.ShapeTool_s(doc.Main())
    tool.SetAutoNaming_s(False)
    top = tool.NewShape() if assembly else None
    if assembly:
        TDataStd_Name.Set_s(top, TCollection_ExtendedString(name))
    for part_name, shape, placement in solids:
        label = tool.AddShape(_unlocated(getattr(shape, "wrapped", shape)), False)
        TDataStd_Name.Set_s(label, TCollection_ExtendedString(part_name))
        if assembly:
            comp = tool.AddComponent(top, label, _location(placement))
            TDataStd_Name.Set_s(comp, TCollection_ExtendedString(part_name))
    tool.UpdateAssemblies()
    _quiet()
    STEPControl_Controller.Init_s()
    writer = STEPCAFControl_Writer()
    writer.SetNameMode(True)
    Interface_Static.SetCVal_s("write.step.unit", "MM")
    Interface_Static.SetIVal_s("write.surfacecurve.mode", 1)
    writer.Transfer(doc, STEPControl_StepModelType.STEPControl_AsIs)
    header = APIHeaderSection_MakeHeader(writer.Writer().Model())
    header.SetName(TCollection_HAsciiString(Path(path).name))
    header.SetOriginatingSystem(TCollection_HAsciiString("rotorkin"))
    if title:
        header.SetDescriptionValue(1, TCollection_HAsciiString(_p21(title)))
    path = Path(path)
    if writer.Write(str(path)) != IFSelect_ReturnStatus.IFSelect_RetDone:  # pragma: no cover
        raise RotorkinError(f"could not write the STEP file {path.name}")
    return path


def read_step(path) -> tuple[list[tuple[str, object]], dict]:
    """The named solids of a STEP file, placed, and its header.

    Returns
    -------
    (solids, header)
        ``[(product name, TopoDS_Shape in mm, placed)]`` for every leaf product, in
        file order, and ``{"name", "description", "unit"}`` of the header
        (``unit``: the length unit's name in the file, e.g. ``"MILLI"``).
    """
    from OCP.collections import Sequence_TDF_Label as TDF_LabelSequence
    from OCP.IFSelect import IFSelect_ReturnStatus
    from OCP.STEPCAFControl import STEPCAFControl_Reader
    from OCP.TCollection import TCollection_ExtendedString
    from OCP.TDataStd import TDataStd_Name
    from OCP.TDF import TDF_Label
    from OCP.TDocStd import TDocStd_Document
    from OCP.XCAFApp import XCAFApp_Application
    from OCP.XCAFDoc import XCAFDoc_DocumentTool, XCAFDoc_ShapeTool

    doc = TDocStd_Document(TCollection_ExtendedString("XmlOcaf"))
    XCAFApp_Application.GetApplication_s().NewDocument(TCollection_ExtendedString("MDTV-XCAF"),
                                                       doc)  # fmt: skip
    _quiet()
    reader = STEPCAFControl_Reader()
    reader.SetNameMode(True)
    if reader.ReadFile(str(path)) != IFSelect_ReturnStatus.IFSelect_RetDone:
        raise RotorkinError(f"cannot read the STEP file {path}")
    reader.Transfer(doc)
    tool = XCAFDoc_DocumentTool.ShapeTool_s(doc.Main())

    def name_of(label) -> str:
        attr = TDataStd_Name()
        if label.FindAttribute(TDataStd_Name.GetID_s(), attr):
            return attr.Get().ToExtString()
        return ""

    out = []

    def walk(label, loc):
        if XCAFDoc_ShapeTool.IsAssembly_s(label):
            comps = TDF_LabelSequence()
            XCAFDoc_ShapeTool.GetComponents_s(label, comps)
            for i in range(1, comps.Length() + 1):
                comp = comps.Value(i)
                ref = TDF_Label()
                XCAFDoc_ShapeTool.GetReferredShape_s(comp, ref)
                walk(ref, loc.Multiplied(XCAFDoc_ShapeTool.GetLocation_s(comp)))
            return
        shape = XCAFDoc_ShapeTool.GetShape_s(label)
        out.append((name_of(label), shape.Moved(loc)))

    from OCP.TopLoc import TopLoc_Location

    free = TDF_LabelSequence()
    tool.GetFreeShapes(free)
    for i in range(1, free.Length() + 1):
        walk(free.Value(i), TopLoc_Location())
    return out, _step_header(path)


def _step_header(path) -> dict:
    """``FILE_NAME`` name, ``FILE_DESCRIPTION`` text and the length unit, read as text."""
    import re

    text = Path(path).read_text(errors="replace")
    head = re.sub(r"[\r\n]", "", text.split("ENDSEC;", 1)[0])  # ISO 10303-21: line ends void
    desc = re.search(r"FILE_DESCRIPTION\s*\(\s*\(\s*'((?:[^']|'')*)'", head)
    name = re.search(r"FILE_NAME\s*\(\s*'((?:[^']|'')*)'", head)
    unit = re.search(r"SI_UNIT\s*\(\s*\.(\w+)\.\s*,\s*\.METRE\.", text)
    return {
        "description": _from_p21(desc.group(1).replace("''", "'")) if desc else "",
        "name": name.group(1).replace("''", "'") if name else "",
        "unit": unit.group(1) if unit else "",
    }
