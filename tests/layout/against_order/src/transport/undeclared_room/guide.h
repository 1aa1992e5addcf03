// A file in a room the order does not declare: the check must ask for its place.
#pragma once
