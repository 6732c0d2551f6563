"""The workbench's GUI half: commands, task panel, view provider, recompute with progress. Importing
it (the workbench does when it is activated; a saved document's view providers do when it opens)
sets the App feature's view-provider and recompute hooks: the App modules never import this
package."""
from .. import feature as _feature
from . import recompute as _recompute
from . import view_provider as _view_provider

_feature.set_view_provider_hook(_view_provider.ViewProviderRemesh)
_feature.set_recompute_hook(_recompute.remesh)
