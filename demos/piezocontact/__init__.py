"""piezocontact's Python side: the twin solver and the tools that compare it
with the C++ solver. The physics is in forms/piezo_forms.py, not here."""
