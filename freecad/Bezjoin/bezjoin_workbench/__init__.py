"""The bezjoin workbench for FreeCAD: plain operations (``operations``) and thin GUI commands
(``commands``).

Importing this package makes the ``bezjoin`` Python bindings importable: when
``import bezjoin`` fails it adds, in order, the folder named by the environment
variable ``BEZJOIN_PYTHON_PATH``, the folder ``bindings/python`` of the
repository this workbench belongs to (found through the real path, so a
symbolic link ``Mod/Bezjoin -> <repo>/freecad/Bezjoin`` works), and the
workbench folder itself (a copied ``bezjoin`` package next to it).
"""

import os
import sys

PYTHON_PATH_VARIABLE = "BEZJOIN_PYTHON_PATH"


def binding_folders():
    """Folders that may hold the ``bezjoin`` package, in the order they are tried."""
    here = os.path.dirname(os.path.realpath(__file__))
    workbench = os.path.dirname(here)
    repository = os.path.dirname(os.path.dirname(workbench))
    folders = []
    explicit = os.environ.get(PYTHON_PATH_VARIABLE, "")
    if explicit:
        folders.append(explicit)
    folders.append(os.path.join(repository, "bindings", "python"))
    folders.append(workbench)
    return folders


def ensure_bindings_importable():
    """Make ``import bezjoin`` work (see the module documentation); return the module."""
    try:
        import bezjoin  # noqa: PLC0415
    except ImportError:
        for folder in binding_folders():
            if os.path.isfile(os.path.join(folder, "bezjoin", "__init__.py")):
                if folder not in sys.path:
                    sys.path.insert(0, folder)
                break
        import bezjoin  # noqa: PLC0415
    return bezjoin
