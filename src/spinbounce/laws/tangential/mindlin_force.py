"""``tangential mindlin/force``: a Mindlin variant (:mod:`.mindlin`)."""

from .mindlin import Mindlin

LAW = Mindlin("mindlin/force")
