"""The arch drawer of Computer Exercise 1 ("Writing our first node")."""
