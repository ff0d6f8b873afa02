"""Counts for messages: exact integers that may be too long to write out in full.

Python refuses to turn an integer of more than 4,300 digits into text
(``sys.set_int_max_str_digits``), and writing one of 100,000 digits takes seconds.
Counts of design spaces (``|SET| ** n_edges``) and of symmetries grow that large, so a
message shows them through :func:`count_text`.
"""

from __future__ import annotations

import math


def count_text(n: int) -> str:
    """``n`` for a message: ``"1,234,567"``, or ``"8.9e+5123"`` past 15 digits (never a huge decimal string).

    Examples
    --------
    >>> count_text(1234567), count_text(5**7320)
    ('1,234,567', '2.9e+5116')
    """
    if n < 10**15:
        return f"{n:,}"
    shift = max(n.bit_length() - 53, 0)
    exponent = math.log10(n >> shift) + shift * math.log10(2)
    whole = math.floor(exponent)
    mantissa = f"{10 ** (exponent - whole):.2g}"
    return f"1e+{whole + 1}" if mantissa == "10" else f"{mantissa}e+{whole}"
