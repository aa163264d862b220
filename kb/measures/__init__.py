"""Reading numbers and units, shared by the description parser (``recall/``) and the extractor (``scrapers/``).

- :mod:`kb.measures.numbers`: numbers written in digits (decimal commas or points by a locale rule passed
  in, thousands separators);
- :mod:`kb.measures.units`: the unit words and their factors to catalog units (cm, g);
- :mod:`kb.measures.text`: text made readable for those rules (invisible marks, full-width forms,
  fractions, feet and inches, times signs).

Nothing else in the project parses numerals or unit names. The package imports nothing above ``kb``.
"""
