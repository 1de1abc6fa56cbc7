#pragma once
// Image bytes a request carries in its body (base64 PNG, pick_request.h), written into a
// private temporary folder for the lifetime of the request, so that they are read and
// checked by the very code that reads paths (pick_inputs.h); removed when it ends.
#include <string>

#include "host/pick/pick_inputs.h"
#include "host/service/pick_request.h"

namespace flexsight {

class RequestImages {
 public:
  explicit RequestImages(const PickRequest& request);
  ~RequestImages();
  RequestImages(const RequestImages&) = delete;
  RequestImages& operator=(const RequestImages&) = delete;

  // The files to read: the request's paths, or the temporary files of its bytes.
  const PickInputFiles& files() const { return files_; }
  // The inputs as PICKS.json names them: the paths, or "body:left_png" and the like.
  const PickInputFiles& described() const { return described_; }
  // `message` with the temporary files named as the request named them ("body:left_png").
  std::string in_request_terms(std::string message) const;

 private:
  std::string folder_;  // empty when the request gave paths only
  PickInputFiles files_, described_;
};

}  // namespace flexsight
