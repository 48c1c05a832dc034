"""A Rounding built on a Deck, exported as that deck rounded, in the deck's own format.

    deck = MeshRound.open_deck("die.k")
    rounding = MeshRound.make_rounding(deck, seeds, 5.0)          # or a Rounding of a Rounding of the Deck
    res = MeshRound.export_deck(rounding, "die_r5.k")             # decks.DeckRoundingResult of the last stage

The Roundings from the Deck up to `rounding` are applied to the deck file in turn with decks.round_deck
(decks.change_radius_deck for one whose Operation changes the radius of existing rounds), each with the feature's own Seeds, Radius or radius law, Tolerance, FeatureAngle, Reach and band element
controls (ElementAngle, ElementLength, MaxAspectRatio); the decks in
between go to a temporary folder.  So the deck written is exactly what round_deck writes: every line, ID,
part and set outside the rounds kept byte for byte (README, "Solver decks").  Refused with RoundingError
(code invalid_input, nothing written): an object that is not a Rounding, a Rounding whose Base chain does
not end at a Deck, an output of another format family than the deck's (no conversion), an output over the
deck's own file, a moved Deck (its Placement is not applied to the file), a Rounding that failed.
"""
import os
import tempfile

from . import decks
from .deck_formats import deck_family
from .errors import RoundingError
from .progress import busy

__all__ = ["export_deck", "deck_chain"]

FAMILY_NAMES = {"lsdyna": "LS-DYNA (.k .key .dyn)", "nastran": "Nastran (.bdf .nas .dat)",
                "abaqus": "Abaqus (.inp)"}


def _is_rounding(obj):
    from .objects.rounding import Rounding
    return isinstance(getattr(obj, "Proxy", None), Rounding)


def _is_deck(obj):
    from .objects.deck import Deck
    return isinstance(getattr(obj, "Proxy", None), Deck)


def deck_chain(rounding):
    """(deck, [roundings from the one on the deck up to `rounding`]); RoundingError unless `rounding` is a
    Rounding whose Base chain ends at a Deck."""
    if not _is_rounding(rounding):
        label = getattr(rounding, "Label", repr(rounding))
        raise RoundingError(f"'{label}' is not a Rounding: select the Rounding to export", code="invalid_input")
    chain, obj = [], rounding
    while _is_rounding(obj):
        if obj in chain:
            raise RoundingError(f"'{obj.Label}' is its own base (a cycle of Roundings)", code="invalid_input")
        chain.append(obj)
        obj = obj.Base
    if not _is_deck(obj):
        what = "nothing" if obj is None else f"'{obj.Label}' (a {obj.TypeId}, not a Deck)"
        raise RoundingError(f"'{rounding.Label}' is not built on a solver deck: its Base chain ends at {what}; "
                            "open the deck with MeshRound.open_deck (or File > Open) and round that",
                            code="invalid_input")
    return obj, chain[::-1]


def export_deck(rounding, out_path, quad_options=None):
    """Write the deck under `rounding` (a Rounding, or a chain of them, on a Deck), rounded as the feature
    rounds it, to out_path (the deck's own format family).  Returns the last round_deck's
    DeckRoundingResult; its report["export_stages"] holds each stage's report["deck"]."""
    deck, chain = deck_chain(rounding)
    out_path = os.path.abspath(os.fspath(out_path))
    family, out_family = deck_family(deck.File), deck_family(out_path)
    if out_family != family:
        what = "not a solver deck" if out_family is None else f"in the {FAMILY_NAMES[out_family]} format"
        raise RoundingError(f"'{out_path}' is {what}, but '{deck.Label}' is in the {FAMILY_NAMES[family]} format: "
                            "export writes the deck's own format (no conversion between formats)",
                            code="invalid_input")
    if out_path == os.path.abspath(deck.File):
        raise RoundingError(f"'{out_path}' is the file of '{deck.Label}': export to another file",
                            code="invalid_input")
    if not os.path.isdir(os.path.dirname(out_path)):
        raise RoundingError(f"cannot write '{out_path}': no such folder", code="invalid_input")
    if not deck.Placement.isIdentity():
        raise RoundingError(f"'{deck.Label}' has been moved (its Placement is not the identity): the deck's "
                            "coordinates would not match the rounding's; reset its Placement", code="invalid_input")
    for obj in chain:
        if "Invalid" in obj.State:
            raise RoundingError(f"'{obj.Label}' failed to recompute ({obj.getStatusString()}): fix it first",
                                code="invalid_input")
    stages = []
    with tempfile.TemporaryDirectory(prefix="meshround-export-", dir=os.path.dirname(out_path)) as folder:
        source = deck.File
        for index, obj in enumerate(chain):
            last = index == len(chain) - 1
            target = out_path if last else os.path.join(folder, f"stage{index}", os.path.basename(deck.File))
            if not last:
                os.makedirs(os.path.dirname(target))
            with busy(f"Exporting {obj.Label} as a deck (Esc cancels)") as token:
                result = _deck_edit(obj)(source, target, list(obj.Seeds), _radius(obj),
                                          tolerance=obj.Tolerance.Value or None,
                                          feature_angle=obj.FeatureAngle.Value, reach=obj.Reach,
                                          quad_options=quad_options, cancel=token, band=_band(obj))
            stages.append(result.report["deck"])
            source = target
    result.report["export_stages"] = stages
    return result


def _deck_edit(obj):
    """The deck edit obj's Operation makes: decks.round_deck, or change_radius_deck for a Rounding that
    changes the radius of existing rounds."""
    from .objects.rounding import CHANGE_RADIUS
    return decks.change_radius_deck if getattr(obj, "Operation", None) == CHANGE_RADIUS else decks.round_deck


def _radius(obj):
    from .objects.rounding import radius_argument
    return radius_argument(obj)


def _band(obj):
    from .objects.rounding import band_argument
    return band_argument(obj)
