"""Wheel–rail geometry: wheelset and track, contact search, contact tables, conicity.

Public names: :class:`Wheelset`, :class:`Track`, :func:`contact_points`,
:func:`contact_table`, :func:`equivalent_conicity`, :func:`elastic_contact`,
:func:`separation`, :func:`undeformed_distance`; :class:`ContactWarning` (a
derailed wheel) and :data:`STATUS` (row status codes of contact tables).
"""

from .conicity import equivalent_conicity
from .contact_search import STATUS, ContactWarning
from .contact_table import contact_table
from .elastic import ElasticContactResult, elastic_contact
from .points import ContactPointsResult, SideContacts, contact_points
from .separation import Separation, separation, undeformed_distance
from .track import Track
from .wheelset import Wheelset

__all__ = ["Wheelset", "Track", "contact_points", "ContactPointsResult", "SideContacts", "contact_table",
           "ContactWarning", "STATUS",
           "equivalent_conicity", "elastic_contact", "ElasticContactResult",
           "separation", "undeformed_distance", "Separation"]
