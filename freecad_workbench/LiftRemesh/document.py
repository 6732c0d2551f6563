"""Changing a FreeCAD document so that a failure leaves it exactly as it was and a success is one
undo step. Shared by the remesh features and the FEM hand-off."""
import contextlib

import FreeCAD


@contextlib.contextmanager
def document_change(doc, title):
    """One undo transaction around a document change; on any error it is aborted and every object
    added meanwhile removed, then the error is raised again. With undo off (FreeCADCmd's default)
    there is no transaction, aborting would keep the objects: removing them is what undoes the
    change. When the caller already has a transaction open (e.g. a command making several FEM
    meshes in one undo step), the change joins it: opening another would commit the caller's; on
    an error only this change's objects are removed and the caller decides."""
    before = {obj.Name for obj in doc.Objects}
    own = bool(doc.UndoMode) and not transaction_open(doc)
    if own:
        doc.openTransaction(title)
    try:
        yield
    except BaseException:
        if own:
            doc.abortTransaction()
        for name in [o.Name for o in doc.Objects if o.Name not in before]:
            if doc.getObject(name) is not None:
                doc.removeObject(name)
        raise
    if own:
        doc.commitTransaction()


def transaction_open(doc):
    """True when a transaction is already open for `doc`: FreeCAD opens it for the application
    (FreeCAD.getActiveTransaction) and gives the document its part on the first change
    (HasPendingTransaction)."""
    return doc.HasPendingTransaction or FreeCAD.getActiveTransaction() is not None
