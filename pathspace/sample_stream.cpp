#include "pathspace/sample_stream.h"

namespace dp::pathspace {

float PrimarySampleStream::next() {
  if (m_index == m_samples.size()) m_samples.push_back(m_rng.uniform());
  return m_samples[m_index++];
}

}  // namespace dp::pathspace
