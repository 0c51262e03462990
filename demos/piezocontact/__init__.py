"""piezocontact's Python side: the twin solver and the tools that compare it
with the C++ solver. The physics is in forms/piezo_forms.py, not here."""

import logging as _logging

# ffcx calls logging.basicConfig() and the cffi JIT then logs every compiler
# call at INFO on the root logger: keep the root handler at WARNING.
_logging.basicConfig()
for _handler in _logging.getLogger().handlers:
    _handler.setLevel(_logging.WARNING)
